"""Overturning acceleration spectra: of one record, of a site, and characteristic curves.

Theory: docs/theory.md §2 (the OAS and its boundary), §11.2 (characteristic site OAS),
§11.4 (site OAS of any structure).

The OAS of any system over p × ap/ap,min with its bisected boundary
(:mod:`~rockarch.spectra.oas`), the site OAS of a suite of records, envelope and percentile
(:mod:`~rockarch.spectra.site`), and the characteristic site OAS, normalised over p·Tm and
simplified from two pulse durations (:mod:`~rockarch.spectra.characteristic`)."""
