"""The source paper, reproduced: its reference numbers, tables and figures.

Theory: the paper's Tables 1, 2, Sects. 8, 9 and Figs. 2, 3, 15–17, 19, through docs/theory.md
§1–§7 (comparisons in docs/validation.md).

Its reference numbers (:mod:`~rockarch.paper.reference`: Tables 1, 2, Sects. 8, 9), its
tables and figures computed with rockarch (:mod:`~rockarch.paper.results`,
:mod:`~rockarch.paper.background`: Figs. 2, 3) and ``rockarch reproduce``
(:mod:`~rockarch.paper.reproduce`)."""
