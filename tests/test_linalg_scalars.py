"""skxfem.linalg.scalars: what every scalar argument takes for a number, and the
arguments that go through it (numpy's numbers and 0-d arrays accepted, bools refused)."""
import numpy as np
import pytest
from skfem import MeshTri1

from skxfem.fem.material import Material
from skxfem.levelset import LevelSet, plane
from skxfem.linalg.choice import check_linear_tol
from skxfem.linalg.scalars import is_integer, is_number, scalar
from skxfem.scene import Interface, Scene
from skxfem.scene.settings import check_max_iter


@pytest.mark.parametrize("v", [3, np.int8(3), np.uint16(3), np.int64(3), np.array(3)])
def test_integers(v):
    assert is_integer(v) and is_number(v) and scalar(v) == 3


@pytest.mark.parametrize("v", [True, np.bool_(False), np.array(True), 3.0, np.array(3.0),
                               "3", None, [3], np.array([3]), 3 + 0j])
def test_not_integers(v):
    assert not is_integer(v)


@pytest.mark.parametrize("v", [True, np.array(True), "0.2", None, np.array([0.2]), 1j,
                               np.array(1j)])
def test_not_numbers(v):
    assert not is_number(v)


def test_arguments_take_zero_d_arrays():
    """Each argument a notebook may compute with numpy: the same scene as with Python's
    numbers (quadrature_order, max_iter, linear_tol, E, a level set's dim)."""
    mesh = MeshTri1.init_tensor(np.linspace(0, 1, 3), np.linspace(0, 1, 3))
    psi = plane((0.5, 0), (1, 0))
    assert Scene(mesh, psi, quadrature_order=np.array(2)).quadrature_order == 2
    assert type(Scene(mesh, psi, quadrature_order=np.int32(2)).quadrature_order) is int
    assert check_max_iter(np.array(7)) == 7
    assert check_linear_tol(np.float32(0.5)) == 0.5
    assert Material(np.array(2e11), np.array(0.3)) == Material(2e11, 0.3)
    assert LevelSet(lambda x: x[0], np.array(2)).dim == 2
    for bad in (np.array(True), np.array(2.0), np.array([2])):
        with pytest.raises(ValueError, match="quadrature_order"):
            Scene(mesh, psi, quadrature_order=bad)
        with pytest.raises(ValueError, match="max_iter"):
            check_max_iter(bad)


def test_unnamed_front_is_phi():
    """A front given as an unnamed LevelSet is 'phi' in messages, not ψ's 'psi'."""
    psi = LevelSet(lambda x: x[1] - 0.5, 2)
    crack = Interface(psi, law="free", front=LevelSet(lambda x: x[0] - 0.5, 2))
    assert (crack.levelset.name, crack.front.name) == ("psi", "phi")
    named = Interface(psi, law="free", front=plane((0.5, 0), (1, 0)))
    assert named.front.name == plane((0.5, 0), (1, 0)).name
