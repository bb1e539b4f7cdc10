"""rockfit.validate: the predictive check equals `rockfit validate --json` on the same campaign."""
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
