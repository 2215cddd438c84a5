"""From spectra to risk (docs/theory.md §11.3): one record's incremental dynamic analysis as
a sweep task (:mod:`~rockarch.risk.record_scan`) and fragility curves over a suite, censored
lognormal fit and bootstrap band (:mod:`~rockarch.risk.fragility`)."""
