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


def test_zquad_is_a_sequence_and_its_groups_of_four_are_base4_nets():
    assert "zquad" in ss.sequences()
    ps = ss.PixelSampler("zquad", 256, 3, resolution=(8, 8))
    v = ps.sample([2, 5], np.arange(256), dims=8)
    # dimensions 0-3 (draws 0 and 2) of the first 4^4 samples: one point in every base-4 box of
    # volume 4^-4, counted; dimensions 2-5 (two groups) are not a (0,4,4)-net
    def is_base4_net(pts):
        for a in range(5):
            for b in range(5 - a):
                for c in range(5 - a - b):
                    d = 4 - a - b - c
                    cells = np.floor(pts * 4.0 ** np.array([a, b, c, d])).astype(int)
                    if len({tuple(r) for r in cells}) != 256:
                        return False
        return True

    assert is_base4_net(v[:, 0:4])
    assert not is_base4_net(v[:, 2:6])
    # dimensions 0-1 alone are a (0,8,2)-net, as zsobol's first draw
    assert ss.net_t_value(v[:, 0:2]) == 0
