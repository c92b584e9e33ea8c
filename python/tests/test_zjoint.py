"""zjoint through the binding: the same values as zsobol with groups of two dimensions, and a
group's draws stratified jointly (the first coordinates of two draws of one group are a net)."""

import numpy as np
import pytest

import strata_sampling as ss


def test_zjoint_is_a_sequence_and_zjoint_2_is_zsobol():
    assert "zjoint" in ss.sequences()
    a = ss.PixelSampler("zsobol", 16, 5, resolution=(8, 8))
    b = ss.PixelSampler("zjoint-2", 16, 5, resolution=(8, 8))
    for pixel in ([0, 0], [3, 7], [9, 2]):
        va = a.sample(pixel, np.arange(16), dims=8)
        vb = b.sample(pixel, np.arange(16), dims=8)
        np.testing.assert_array_equal(va, vb)


def test_a_group_is_stratified_jointly():
    ps = ss.PixelSampler("zjoint", 64, 3, resolution=(8, 8))
    v = ps.sample([2, 5], np.arange(64), dims=8)
    # draw 0 and draw 1 of the group, first coordinates: Sobol' dimensions 0 and 2, a (1,6,2)-net
    assert ss.net_t_value(np.stack([v[:, 0], v[:, 2]], axis=1)) == 1


@pytest.mark.parametrize("bad", ["zjoint-3", "zjoint-0", "zjoint-1024", "zjoint-x"])
def test_bad_groups_are_refused(bad):
    with pytest.raises(ValueError, match="zjoint"):
        ss.PixelSampler(bad, 16, resolution=(8, 8))
