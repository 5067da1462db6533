"""pgmcl.Map, load_map, save_map: the grid's metadata, cells as a numpy view of the map's
own memory, maps built from numpy, and round trips through map_server files."""

import gc

import numpy as np
import pytest

import pgmcl


def test_load_map_reads_the_yaml_and_the_image(intel):
    m = pgmcl.load_map(intel / "map.yaml")
    # `pgmcl map` printed: 849 x 810 cells at 0.050 m, origin (-20.900, -26.700).
    assert (m.width, m.height, m.resolution) == (849, 810, 0.05)
    assert m.origin == pytest.approx((-20.9, -26.7, 0.0))
    assert m.cells.shape == (810, 849) and m.cells.dtype == np.int8
    assert set(np.unique(m.cells)) <= {-1, 0, 100}
    assert 0.25 < np.mean(m.cells == 0) < 0.35  # "30.0 % free"


def test_cells_is_a_view_of_the_map_not_a_copy(intel):
    m = pgmcl.load_map(intel / "map.yaml")
    a, b = m.cells, m.cells
    assert not a.flags.owndata and a.flags.writeable
    assert np.shares_memory(a, b)
    a[0, 0] = 100
    assert b[0, 0] == 100
    cells = m.cells
    total = int(cells.astype(np.int64).sum())
    del m, a, b
    gc.collect()
    assert int(cells.astype(np.int64).sum()) == total  # the view keeps the map alive


def test_writes_through_the_view_reach_the_saved_file(tmp_path):
    m = pgmcl.Map(np.zeros((20, 30), np.int8), 0.1)
    m.cells[5, 7] = 100  # row 5 (y = 0.5..0.6 m), column 7
    m.save(tmp_path / "m.yaml")
    back = pgmcl.load_map(tmp_path / "m.yaml")
    assert back.cells[5, 7] == 100 and int((back.cells == 100).sum()) == 1


def test_a_map_from_numpy_round_trips_through_files(tmp_path):
    cells = np.zeros((40, 50), dtype=np.int64)  # any integer dtype, copied once
    cells[0, :] = cells[-1, :] = cells[:, 0] = cells[:, -1] = 100
    cells[10:20, 30:35] = -1
    m = pgmcl.Map(cells, 0.05, origin=(1.5, -2.0, 0.25))
    cells[1, 1] = 100  # the map holds its own copy
    assert m.cells[1, 1] == 0
    for mode, image in (("trinary", None), ("scale", "m.png")):
        pgmcl.save_map(m, tmp_path / f"{mode}.yaml", image=image, mode=mode)
        back = pgmcl.load_map(tmp_path / f"{mode}.yaml")
        assert np.array_equal(back.cells, m.cells), mode
        assert back.origin == pytest.approx(m.origin) and back.resolution == m.resolution


def test_scale_mode_keeps_intermediate_occupancy(tmp_path):
    m = pgmcl.Map(np.array([[0, 30, 100], [-1, 0, 0]]), 0.1)
    m.save(tmp_path / "s.yaml", mode="scale")
    # 30 % is written as grey round(255 * 0.7) = 179 and read back through map_server's
    # scale rule: occ = 1 - 179 / 255, rint((occ - 0.196) / (0.65 - 0.196) * 100) = 22.
    occ = 1 - 179 / 255
    assert round((occ - 0.196) / (0.65 - 0.196) * 100) == 22
    assert pgmcl.load_map(tmp_path / "s.yaml").cells.tolist() == [[0, 22, 100], [-1, 0, 0]]


def test_bad_cells_are_refused_with_the_cell_named():
    with pytest.raises(ValueError, match=r"cells\[1, 2\] = 101"):
        pgmcl.Map(np.array([[0, 0, 0], [0, 0, 101]]), 0.1)
    with pytest.raises(TypeError, match="integer array"):
        pgmcl.Map(np.zeros((3, 3)), 0.1)
    with pytest.raises(ValueError, match="2-D"):
        pgmcl.Map(np.zeros(9, np.int8), 0.1)
    with pytest.raises(ValueError, match="resolution"):
        pgmcl.Map(np.zeros((3, 3), np.int8), float("nan"))
    with pytest.raises(TypeError, match=r"origin: expected \(x, y, theta\)"):
        pgmcl.Map(np.zeros((3, 3), np.int8), 0.1, origin=(1, 2))


def test_extent_and_threshold():
    m = pgmcl.Map(np.zeros((10, 20), np.int8), 0.5, origin=(-1.0, 2.0, 0.0))
    assert m.extent == (-1.0, 9.0, 2.0, 7.0)
    assert m.occupied_threshold == 65
    m.occupied_threshold = 50
    assert m.occupied_threshold == 50
    with pytest.raises(ValueError):
        m.occupied_threshold = 0
