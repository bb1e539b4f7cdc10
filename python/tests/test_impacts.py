"""rockfit.edge_impact and rockfit.facet_impact: the fields of `rockfit impact --json`, bit for bit, and the
energy balance (26)."""
import numpy as np
import pytest

from conftest import as_plain, run_cli

BLOCK = ["--b1", "0.05", "--b2", "0.03", "--h", "0.20", "--mass", "1"]  # the paper's Fig. 11 block



@pytest.fixture(scope="module")
def fig11(rockfit):
    return rockfit.Block(0.05, 0.03, 0.20, mass=1)


@pytest.mark.parametrize("lambda_lat,lambda_lon,tau", [(0.3, 0.8, None), (-0.5, 0.2, None), (0.3, 0.8, 1e-4)])
def test_facet_impact_equals_the_program_json(rockfit, fig11, lambda_lat, lambda_lon, tau):
    result = rockfit.facet_impact(fig11, omega_minus=[0, 1, 0], pivot_edge=(1, 2), lambda_lat=lambda_lat,
                                  lambda_lon=lambda_lon, tau=tau)
    args = ["impact", "facet", *BLOCK, "--pivot-edge", "1,2", "--omega-minus", "0,1,0",
            "--lambda-lat", lambda_lat, "--lambda-lon", lambda_lon]
    if tau is not None:
        args += ["--tau", tau]
    cli = run_cli(*args, check=False)
    assert set(result.keys()) == set(cli.keys())
    for key, expected in cli.items():
        assert as_plain(result[key]) == expected, key


def test_edge_impact_equals_the_program_json(rockfit, fig11):
    result = rockfit.edge_impact(fig11, pivot=4, landing=3, tilt=0.03, omega_minus=[-0.4, 0.6, 0], lambda_=0.6)
    cli = run_cli("impact", "edge", *BLOCK, "--pivot", 4, "--landing", 3, "--tilt", 0.03,
                  "--omega-minus=-0.4,0.6,0", "--lambda", 0.6, check=False)
    assert set(result.keys()) == set(cli.keys())
    for key, expected in cli.items():
        assert as_plain(result[key]) == expected, key


def test_facet_impact_loses_energy_and_matches_26(rockfit, fig11):
    result = rockfit.facet_impact(fig11, omega_minus=np.array([0.0, 1.0, 0.0]), lambda_lat=0.3, lambda_lon=0.8)
    assert result.status == "ok" and result.contact_after == "V4"
    # (26): ΔE = E⁺ − E⁻ ≤ 0; E⁻ = ½ωᵀ(Θ + m R_bᵀR_b)ω about the pivot V2 for ω = (0, 1, 0).
    theta_yy = 1 / 3 * (0.05**2 + 0.2**2)
    assert result.energy_before == pytest.approx(0.5 * (theta_yy + (0.05**2 + 0.2**2)), rel=1e-12)
    assert result.delta_energy == pytest.approx(result.energy_after - result.energy_before, rel=1e-12)
    assert result.delta_energy <= 0 and result.energy_nonincreasing


def test_singular_lambdas_make_the_edge_map_singular(rockfit, fig11):
    result = rockfit.edge_impact(fig11, pivot=4, landing=3, tilt=0.03, omega_minus=[-0.4, 0.6, 0])
    assert result.singular_lambdas, "the edge map of this block has a singular λ"
    at_root = rockfit.edge_impact(fig11, pivot=4, landing=3, tilt=0.03, omega_minus=[-0.4, 0.6, 0],
                                  lambda_=result.singular_lambdas[0])
    assert at_root.status == "singular" and at_root.omega_plus is None


def test_bad_impact_arguments_are_value_errors(rockfit, fig11):
    with pytest.raises(ValueError, match="pivot must be a base vertex"):
        rockfit.edge_impact(fig11, pivot=5, landing=1, omega_minus=[0, 1, 0])
    with pytest.raises(ValueError, match="landing must be a neighbour"):
        rockfit.edge_impact(fig11, pivot=1, landing=3, omega_minus=[0, 1, 0])
    with pytest.raises(ValueError, match="omega_minus must be a vector of 3"):
        rockfit.facet_impact(fig11, omega_minus=[0, 1])
    with pytest.raises(ValueError, match="finite"):
        rockfit.facet_impact(fig11, omega_minus=[0, 1, 0], lambda_lat=float("nan"))
