"""OAS: grid map, boundary bisection without monotonicity, NetCDF round trip."""

from dataclasses import dataclass

import numpy as np
import pytest

from rockarch import systems
from rockarch.motion import signals as mo
from rockarch.motion.records import el_centro
from rockarch.rocking.block import RigidBlock, simulate_batch
from rockarch.spectra import oas as spectra


@dataclass(frozen=True)
class Islands:
    """A fake system that overturns for ratio in [2, 3) ∪ [3.5, ∞): a safe island."""

    name: str = "islands"

    def run(self, motion, p, ratio):
        r = np.asarray(ratio, dtype=float)
        o = ((r >= 2.0) & (r < 3.0)) | (r >= 3.5)
        return o, o.astype(float)

    def attrs(self):
        return {"kind": "test"}


def test_boundary_is_lowest_overturning_and_islands_stay():
    ratio = np.linspace(1.0, 5.0, 17)  # step 0.25
    ds = spectra.compute_oas(Islands(), mo.sine(1, 1), [1.0, 2.0], ratio, tol=1e-4,
                             progress=False)
    # bisection between 1.75 (safe) and 2.0: converges on 2.0 from above within tol
    assert ds.boundary.values == pytest.approx([2.0, 2.0], abs=1e-4)
    assert np.all(ds.boundary.values >= 2.0)  # the boundary is an overturning ratio
    row = ds.overturned.values[0]
    assert not row[ratio == 3.25][0]  # the safe island above the boundary is kept
    assert row[ratio == 3.5][0] and row[ratio == 2.5][0]


def test_no_refinement_gives_first_grid_cell_and_nan_when_safe():
    ratio = np.array([1.0, 1.5, 2.5])
    ds = spectra.compute_oas(Islands(), mo.sine(1, 1), [1.0], ratio, tol=0, progress=False)
    assert ds.boundary.values[0] == 2.5
    ds = spectra.compute_oas(Islands(), mo.sine(1, 1), [1.0], [1.0, 1.5], progress=False)
    assert np.isnan(ds.boundary.values[0])


def test_block_oas_map_equals_batch_runs_and_roundtrips(tmp_path):
    rec = el_centro()
    p = np.linspace(1.0, 6.0, 6)
    ratio = np.linspace(1.0, 3.0, 9)
    system = systems.BlockSystem(alpha=0.1)
    ds = spectra.compute_oas(system, rec, p, ratio, progress=False)
    pp, rr = np.meshgrid(p, ratio, indexing="ij")
    direct = simulate_batch(RigidBlock(1.0, 0.1), rec, pp, rr)
    assert np.array_equal(ds.overturned.values, direct.overturned)
    # the refined boundary lies in (last safe grid value, first overturning grid value]
    for i in range(p.size):
        row = ds.overturned.values[i]
        if row.any():
            k = int(row.argmax())
            lo = ratio[k - 1] if k else 1.0
            assert lo < ds.boundary.values[i] <= ratio[k]
            assert simulate_batch(RigidBlock(1.0, 0.1), rec, p[i],
                                  ds.boundary.values[i]).overturned
    f = tmp_path / "oas.nc"
    spectra.save(ds, f)
    back = spectra.load(f)
    assert back.overturned.dtype == bool
    assert np.array_equal(back.overturned.values, ds.overturned.values)
    assert np.allclose(back.boundary.values, ds.boundary.values, equal_nan=True)
    assert back.attrs["motion_sha256"] == rec.fingerprint()
    assert [x.name for x in tmp_path.iterdir()] == ["oas.nc"]  # no temporary left


def test_slender_block_oas_nearly_independent_of_alpha():
    """Paper Fig. 3a / docs/theory.md §2: for slender blocks the OAS hardly depends on alpha;
    sine pulse boundaries of alpha = 0.02 and 0.05 agree within 1 % (O(α²) effects)."""
    p = [1.5, 3.0, 6.0]
    b = [spectra.compute_oas(systems.BlockSystem(alpha=a), mo.sine(1, 1.0), p,
                             np.linspace(1, 8, 29), progress=False).boundary.values
         for a in (0.02, 0.05)]
    assert np.allclose(b[0], b[1], rtol=1e-2)


@pytest.mark.parametrize(
    "p, ratio, msg",
    [([2.0, 1.0], [1, 2], "strictly increasing"), ([0.0, 1.0], [1, 2], "p values must be > 0"),
     ([1.0], [np.nan], "finite"), ([], [1.0], "non-empty")],
)
def test_bad_grids(p, ratio, msg):
    with pytest.raises(ValueError, match=msg):
        spectra.compute_oas(systems.BlockSystem(alpha=0.1), mo.sine(1, 1), p, ratio,
                            progress=False)


def test_load_rejects_other_files(tmp_path):
    f = tmp_path / "x.nc"
    f.write_text("not netcdf")
    with pytest.raises(ValueError, match="x.nc: not a NetCDF file"):  # one short line
        spectra.load(f)
    f.write_bytes(b"CDF\x01 but cut short")  # the signature, not the file: the reader's
    with pytest.raises(ValueError, match="not a readable NetCDF file") as err:  # first line
        spectra.load(f)
    assert "\n" not in str(err.value) and len(str(err.value)) < 300


def test_oas_load_refuses_a_site_oas_file(tmp_path):
    """A site OAS (record × p × ratio) read as one OAS was taken silently; now a ValueError
    says what it is and what reads it, as site.load says of an OAS file."""
    from rockarch.spectra import site

    motions = [mo.sine(1, 1.0), mo.pulse("sine", period=0.6)]
    ds = site.site_oas(motions, [1.0, 2.0], [1.0, 2.0, 4.0], progress=False)
    f = tmp_path / "site.nc"
    site.save(ds, f)
    with pytest.raises(ValueError, match="site.nc: not an OAS file but a rockarch site OAS "
                                         "file: read it with rockarch.spectra.site.load"):
        spectra.load(f)
    ds.attrs.pop("kind")  # no kind attribute: the record axis still gives it away
    site.save(ds, f)
    with pytest.raises(ValueError, match="not an OAS file but a rockarch site OAS file"):
        spectra.load(f)
    one = spectra.compute_oas(systems.BlockSystem(alpha=0.1), motions[0], [1.0, 2.0],
                              [1.0, 2.0, 4.0], progress=False)
    spectra.save(one, tmp_path / "oas.nc")
    assert spectra.load(tmp_path / "oas.nc").boundary.dims == ("p",)  # an OAS still loads
    with pytest.raises(ValueError, match="not a rockarch site OAS file"):
        site.load(tmp_path / "oas.nc")


def test_site_and_oas_files_state_their_units(tmp_path):
    """A site OAS file's curves carry units and long names as an OAS file's boundary does,
    record_name says how to select by name, and the numeric attributes' units are in the
    file (attribute_units); a file written before (without them) still loads."""
    import rockarch as ra
    from rockarch.spectra import site

    motions = [mo.sine(1, 1.0), mo.pulse("sine", period=0.6)]
    f = tmp_path / "site.nc"
    site.save(site.site_oas(motions, [1.0, 2.0], [1.0, 2.0, 4.0], progress=False), f)
    ds = site.load(f)
    for name in ("boundary", "envelope", "characteristic"):
        assert ds[name].attrs["units"] == "1" and "ap/ap,min" in ds[name].attrs["long_name"]
    assert "swap_dims(record='record_name')" in ds["record_name"].attrs["long_name"]
    assert np.array_equal(ds.swap_dims(record="record_name")["boundary"].sel(
        record_name="sine T=0.6 s").values, ds["boundary"].values[1], equal_nan=True)
    units = dict(u.split(": ") for u in ds.attrs["attribute_units"].split("; "))
    assert units["alpha"] == "rad" and units["t_free"] == "s"
    one = spectra.compute_oas(systems.BlockSystem(alpha=0.1), motions[0], [1.0], [1.0, 2.0],
                              progress=False)
    units = dict(u.split(": ") for u in one.attrs["attribute_units"].split("; "))
    assert (units["system_alpha"], units["system_g"], units["system_ap_min"]) == \
        ("rad", "m/s2", "m/s2")
    other = site.site_oas(motions, [1.0, 2.0], [1.0, 2.0],
                          system=ra.system("sdof", p=2.0, delta=0.2, ap_min=2.0),
                          progress=False)
    assert "system_delta: rad" in other.attrs["attribute_units"]
    old = ds.copy()  # as written before: no attribute_units, no variable attributes
    del old.attrs["attribute_units"]
    for v in old.variables.values():
        v.attrs.clear()
    site.save(old, f)
    assert np.array_equal(site.load(f)["envelope"].values, ds["envelope"].values,
                          equal_nan=True)
