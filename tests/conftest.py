"""Shared test parameters: the five cell types of skxfem, from the library itself.

A test that takes an argument ``cell`` runs once per cell type (``tri``,
``quad``, ``tet``, ``hex``, ``prism``); ``cell_2d`` and ``cell_3d`` run over
the cells of one dimension.  A test that needs other cells parametrizes
``cell`` explicitly, which takes precedence over these fixtures.
"""
import pytest

from skxfem.scene import CELLS

CELLS_2D = [c for c, dim in CELLS.items() if dim == 2]
CELLS_3D = [c for c, dim in CELLS.items() if dim == 3]


@pytest.fixture(params=list(CELLS))
def cell(request) -> str:
    """Each of the five cell types."""
    return request.param


@pytest.fixture(params=CELLS_2D)
def cell_2d(request) -> str:
    """Each 2D cell type."""
    return request.param


@pytest.fixture(params=CELLS_3D)
def cell_3d(request) -> str:
    """Each 3D cell type."""
    return request.param
