"""rockfit.Block: sizes, mass and inertia against the closed forms, the manifest, and errors."""
import pickle

import numpy as np
import pytest

from conftest import MANIFEST


def test_mass_from_density_is_density_times_volume(rockfit):
    block = rockfit.Block(0.05, 0.03, 0.2, density=2692)
    assert block.mass == pytest.approx(2692 * 8 * 0.05 * 0.03 * 0.2, rel=1e-15)
    assert block.density == pytest.approx(2692, rel=1e-15)
    assert (block.b1, block.b2, block.h) == (0.05, 0.03, 0.2)


def test_inertia_is_the_cuboid_closed_form(rockfit):
    b1, b2, h, m = 0.05, 0.03, 0.2, 1.0
    block = rockfit.Block(b1, b2, h, mass=m)
    expected = m / 3 * np.diag([b2**2 + h**2, b1**2 + h**2, b1**2 + b2**2])
    np.testing.assert_allclose(block.inertia_C_B, expected, rtol=1e-15, atol=0)
    np.testing.assert_array_equal(block.p_BC_B, [0, 0, h])


def test_vertices_are_numbered_cyclically(rockfit):
    block = rockfit.Block(0.05, 0.03, 0.2, mass=1)
    np.testing.assert_array_equal(block.vertex(1), [-0.05, -0.03, 0])
    np.testing.assert_array_equal(block.vertex(3), [0.05, 0.03, 0])
    np.testing.assert_array_equal(block.vertex(0), block.vertex(4))
    np.testing.assert_array_equal(block.vertex(5), block.vertex(1))


def test_from_manifest_equals_the_program_block(rockfit):
    from conftest import run_cli
    block = rockfit.Block.from_manifest(str(MANIFEST), "block2")
    cli = run_cli("block", "--manifest", MANIFEST, "--block", "block2")
    assert block.b2 == 0.035
    assert block.mass == cli["mass"]


def test_repr_and_pickle_round_trip(rockfit):
    block = rockfit.Block(0.05, 0.03, 0.2, mass=1.5)
    assert repr(block) == "Block(b1=0.05, b2=0.03, h=0.2, mass=1.5)"
    again = pickle.loads(pickle.dumps(block))
    assert (again.b1, again.b2, again.h, again.mass) == (block.b1, block.b2, block.h, block.mass)


def test_density_and_mass_together_is_a_value_error(rockfit):
    with pytest.raises(ValueError, match="exactly one of density"):
        rockfit.Block(0.05, 0.03, 0.2, density=2692, mass=1)
    with pytest.raises(ValueError, match="exactly one of density"):
        rockfit.Block(0.05, 0.03, 0.2)


def test_non_positive_size_is_a_value_error_naming_it(rockfit):
    with pytest.raises(ValueError, match="b2"):
        rockfit.Block(0.05, -0.03, 0.2, mass=1)


def test_unknown_block_id_is_an_input_error_naming_the_manifest(rockfit):
    with pytest.raises(rockfit.InputError, match="no block 'nope'") as info:
        rockfit.Block.from_manifest(str(MANIFEST), "nope")
    assert info.value.path == str(MANIFEST)
