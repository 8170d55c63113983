"""Data out: pandas, xarray, CSV and NetCDF round trips return the same numbers; Mechanism,
Result and errors pickle."""

from __future__ import annotations

import pickle
import sys

import numpy as np
import pytest

import clearsim


@pytest.fixture(scope="module")
def run():
    m = clearsim.models.slider_crank("dry", clearance=0.5e-3)
    res = m.simulate(0.003, dt_out=1e-4, outputs=["states", "accelerations", "joints", "violation"])
    return m, res


def test_to_pandas_columns_carry_the_numbers_and_units(run):
    pytest.importorskip("pandas")
    _, res = run
    df = res.to_pandas()
    np.testing.assert_array_equal(df.index.to_numpy(), res.t)
    np.testing.assert_array_equal(df["slider.x"].to_numpy(), res.position("slider")[:, 0])
    np.testing.assert_array_equal(df["slider.x_ddot"].to_numpy(), res.acceleration("slider")[:, 0])
    joint = res.joint_names[0]
    np.testing.assert_array_equal(df[f"{joint}.ex"].to_numpy(), res.eccentricity(joint)[:, 0])
    assert df.attrs["units"]["slider.x_ddot"] == "m/s^2"
    assert df.attrs["units"]["crank.theta"] == "rad"


def test_csv_round_trip(run, tmp_path):
    pd = pytest.importorskip("pandas")
    _, res = run
    path = res.save(tmp_path / "run.csv")
    back = pd.read_csv(path)
    assert back.columns[0] == "t [s]" and "slider.y_dot [m/s]" in back.columns
    np.testing.assert_array_equal(back["t [s]"].to_numpy(), res.t)
    np.testing.assert_array_equal(back["slider.y_dot [m/s]"].to_numpy(), res.velocity("slider")[:, 1])
    np.testing.assert_array_equal(back["rod.theta_ddot [rad/s^2]"].to_numpy(), res.acceleration("rod")[:, 2])


def test_netcdf_round_trip(run, tmp_path):
    xr = pytest.importorskip("xarray")
    pytest.importorskip("netCDF4")
    _, res = run
    ds = res.to_xarray()
    assert ds["position"].sel(body="slider", coordinate="x").attrs["units"] == "m, m, rad"
    path = res.save(tmp_path / "run.nc")
    back = xr.open_dataset(path)
    try:
        np.testing.assert_array_equal(back["time"].to_numpy(), res.t)
        np.testing.assert_array_equal(back["position"].sel(body="slider", coordinate="x").to_numpy(), res.position("slider")[:, 0])
        np.testing.assert_array_equal(back["acceleration"].sel(body="crank", coordinate="theta").to_numpy(), res.acceleration("crank")[:, 2])
        joint = res.joint_names[0]
        np.testing.assert_array_equal(back["clearance_joint"].sel(joint=joint, quantity="ey").to_numpy(), res.eccentricity(joint)[:, 1])
        assert back["time"].attrs["units"] == "s"
    finally:
        back.close()


@pytest.mark.parametrize("missing", ["xarray", "netCDF4"])
def test_netcdf_without_its_packages_names_the_extra_to_install(run, tmp_path, monkeypatch, missing):
    """A .nc file needs xarray and netCDF4: without either, save says which and the extra that
    installs both, before anything is written (without netCDF4 xarray wrote a NetCDF 3 file
    through scipy, or failed with its own message)."""
    _, res = run
    monkeypatch.setitem(sys.modules, missing, None)  # ``import missing`` now raises ImportError
    with pytest.raises(ImportError, match=rf"{missing} is needed for saving run\.nc.*pip install 'clearsim\[io\]'"):
        res.save(tmp_path / "run.nc")
    assert not (tmp_path / "run.nc").exists()


def test_save_rejects_an_unknown_format(run, tmp_path):
    _, res = run
    with pytest.raises(clearsim.InputError, match=r"\.csv or \.nc"):
        res.save(tmp_path / "run.xlsx")


def test_mechanism_and_result_pickle_after_a_run(run):
    m, res = run
    m2 = pickle.loads(pickle.dumps(m))
    res2 = pickle.loads(pickle.dumps(res))
    np.testing.assert_array_equal(res2.position("slider"), res.position("slider"))
    again = m2.simulate(0.003, dt_out=1e-4)
    np.testing.assert_allclose(again.position("slider"), res.position("slider"), rtol=0, atol=1e-12)


def test_errors_pickle_with_their_details():
    err = clearsim.InputError("invalid clearance = -1: must be positive", field="clearance", value=-1.0)
    back = pickle.loads(pickle.dumps(err))
    assert isinstance(back, clearsim.InputError) and back.field == "clearance" and back.value == -1.0
    assert str(back) == str(err)
