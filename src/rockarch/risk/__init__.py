"""From spectra to risk: IDA, fragility curves and the annual frequency of collapse.

Theory: docs/theory.md §11.3 (IDA, the search for collapse islands, censored lognormal fit),
§11.5 (hazard curve, annual frequency of collapse, deaggregation).

One record's incremental dynamic analysis as a sweep task
(:mod:`~rockarch.risk.record_scan`), fragility curves over a suite, censored lognormal
fit and bootstrap band (:mod:`~rockarch.risk.fragility`), and a site's hazard curve
combined with a fragility (:mod:`~rockarch.risk.hazard`). Users' guide: docs/sites.md."""
