"""The source paper, reproduced: its reference numbers (:mod:`~rockarch.paper.reference`:
Tables 1, 2, Sects. 8, 9), its tables and figures computed with rockarch
(:mod:`~rockarch.paper.results`, :mod:`~rockarch.paper.background`: Figs. 2, 3) and
``rockarch reproduce`` (:mod:`~rockarch.paper.reproduce`)."""
