"""rockfit.validate: the predictive check equals `rockfit validate --json` on the same campaign, with the release
roll mode passed through."""
import pytest

from conftest import MANIFEST, SAMPLES, requires_optimised_build, run_cli


def two_trial_manifest(tmp_path):
    """block2 in position A: two releases with different impact parameters (data-samples/README.md)."""
    text = MANIFEST.read_text().replace('"recordings/', f'"{SAMPLES}/recordings/')
    head, *trials = text.split("[[trials]]")
    kept = [t for t in trials if 'id = "block2-A-' in t]
    path = tmp_path / "campaign.toml"
    path.write_text(head + "".join("[[trials]]" + t for t in kept))
    return path


@requires_optimised_build
def test_validate_equals_the_program(rockfit, tmp_path):
    manifest = two_trial_manifest(tmp_path)
    result = rockfit.validate(str(manifest), jobs=2, intervals="fast")
    cli = run_cli("validate", manifest, "-j", "2", "--intervals", "fast")
    assert [t["trial"] for t in result.trials] == ["block2-A-1", "block2-A-2"]
    for mine, theirs in zip(result.trials, cli["trials"]):
        assert mine["ratio"] == pytest.approx(theirs["ratio"], rel=1e-12)
        assert mine["parameters"].keys() == theirs["parameters"].keys()
    # The two releases differ in λ, λ_lat and λ_lon: neither predicts the other.
    assert all(t["ratio"] > 1.5 and not t["transfers"] for t in result.trials)
    assert result.groups[0]["n_predicted"] == 2


def test_validate_rejects_a_bad_ratio_warning(rockfit, tmp_path):
    with pytest.raises(ValueError):
        rockfit.validate(str(two_trial_manifest(tmp_path)), ratio_warning=0.5)


# The sample releases were made on the edge: a roll fitted on them is 0 to within micro-radians (fitting/README.md,
# "The release roll in the fit": |β| ≤ 2.6 µrad over the 16 samples); 0.1 mrad is a roll the fall would show.
ROLL_OF_AN_EDGE_RELEASE_RAD = 1e-4


@requires_optimised_build
def test_validate_with_the_release_roll_on_refits_each_left_out_roll_as_the_program_does(rockfit, tmp_path):
    manifest = two_trial_manifest(tmp_path)
    result = rockfit.validate(str(manifest), jobs=2, intervals="fast", release_roll_mode="on")
    cli = run_cli("validate", manifest, "-j", "2", "--intervals", "fast", "--release-roll-mode", "on")
    for mine, theirs in zip(result.trials, cli["trials"]):
        assert mine["release_roll_fitted"] and theirs["release_roll_fitted"]
        assert mine["release_roll"] == pytest.approx(theirs["release_roll"], rel=1e-12, abs=1e-15)
        assert mine["ratio"] == pytest.approx(theirs["ratio"], rel=1e-12)
        assert abs(mine["release_roll"]) < ROLL_OF_AN_EDGE_RELEASE_RAD


def test_validate_rejects_an_unknown_release_roll_mode(rockfit, tmp_path):
    with pytest.raises(ValueError, match="release-roll-mode"):
        rockfit.validate(str(two_trial_manifest(tmp_path)), release_roll_mode="sometimes")
