"""rockarch: seismic overturning assessment of rocking blocks, columns and masonry arches.

The data flow is ``ground motion -> structure -> simulation -> spectrum -> design check``:
:mod:`rockarch.motion` / :mod:`rockarch.records` give a_g(t); :mod:`rockarch.block` is
Housner's rigid block; :mod:`rockarch.spectra` computes overturning acceleration spectra
(OAS); :mod:`rockarch.arch` is masonry arch statics (thrust line, four-hinge mechanism).
"""

__version__ = "0.1.0"
