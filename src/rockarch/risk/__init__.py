"""From spectra to risk: incremental dynamic analysis and fragility curves.

Theory: docs/theory.md §11.3 (IDA, censored lognormal fit).

One record's incremental dynamic analysis as a sweep task
(:mod:`~rockarch.risk.record_scan`) and fragility curves over a suite, censored lognormal
fit and bootstrap band (:mod:`~rockarch.risk.fragility`). Users' guide: docs/sites.md."""
