"""Overturning acceleration spectra (docs/theory.md §2, §11.2): the OAS of any system over
p × ap/ap,min with its bisected boundary (:mod:`~rockarch.spectra.oas`), the site OAS of a
suite of records, envelope and percentile (:mod:`~rockarch.spectra.site`), and the
characteristic site OAS, normalised over p·Tm and simplified from two pulse durations
(:mod:`~rockarch.spectra.characteristic`)."""
