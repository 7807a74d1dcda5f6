"""Replays the random draws of shard's MCA sample builder (src/particle/packing.cpp) in Python,
so that a study script can know which automata the builder made inclusions or pores without
writing them out: std::mt19937_64 with the builder's mapping to [0, 1).

Used by examples/mca_tic_nicr_bending/run_study.py and examples/mca_porous_zirconia/run_study.py,
with hexagonal_sites, the builder's lattice sites in its order.
Written by hand: numpy's MT19937 is the 32-bit generator, and the standard library has neither.
"""

import math

MASK64 = (1 << 64) - 1


class MT19937_64:
    """std::mt19937_64: the 64-bit Mersenne Twister with the C++ standard's parameters."""

    def __init__(self, seed):
        self.mt = [0] * 312
        self.mt[0] = seed & MASK64
        for i in range(1, 312):
            prev = self.mt[i - 1]
            self.mt[i] = (6364136223846793005 * (prev ^ (prev >> 62)) + i) & MASK64
        self.index = 312

    def _twist(self):
        mt = self.mt
        for i in range(312):
            x = (mt[i] & 0xFFFFFFFF80000000) | (mt[(i + 1) % 312] & 0x7FFFFFFF)
            xa = x >> 1
            if x & 1:
                xa ^= 0xB5026F5AA96619E9
            mt[i] = mt[(i + 156) % 312] ^ xa
        self.index = 0

    def __call__(self):
        if self.index >= 312:
            self._twist()
        y = self.mt[self.index]
        self.index += 1
        y ^= (y >> 29) & 0x5555555555555555
        y ^= (y << 17) & 0x71D67FFFEDA60000
        y ^= (y << 37) & 0xFFF7EEE000000000
        y ^= y >> 43
        return y & MASK64

    def uniform01(self):
        """The builder's mapping to [0, 1): the top 53 bits."""
        return (self() >> 11) * 2.0 ** -53


def hexagonal_sites(width, height, d):
    """Centres of the hexagonal packing of [0, width] × [0, height], in the builder's order."""
    a = ((d, 0.0), (0.5 * d, 0.5 * math.sqrt(3.0) * d))
    det = a[0][0] * a[1][1] - a[1][0] * a[0][1]
    inverse = ((a[1][1] / det, -a[1][0] / det), (-a[0][1] / det, a[0][0] / det))
    low, high = [1 << 40] * 2, [-(1 << 40)] * 2
    box = (width, height)
    for corner in range(4):
        c = [box[k] if (corner >> k) & 1 else 0.0 for k in range(2)]
        f = [inverse[r][0] * c[0] + inverse[r][1] * c[1] for r in range(2)]
        for k in range(2):
            low[k] = min(low[k], math.floor(f[k]) - 1)
            high[k] = max(high[k], math.ceil(f[k]) + 1)
    tol = 1e-9 * d
    sites = []
    for j in range(low[1], high[1] + 1):
        for i in range(low[0], high[0] + 1):
            p = (i * a[0][0] + j * a[1][0], i * a[0][1] + j * a[1][1])
            if all(-tol <= p[k] <= box[k] + tol for k in range(2)):
                sites.append(p)
    return sites
