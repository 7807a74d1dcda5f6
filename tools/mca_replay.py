"""Replays the random draws of shard's MCA sample builder (src/particle/packing.cpp) in Python,
so that a study script can know which automata the builder made inclusions or pores without
writing them out: std::mt19937_64 with the builder's mapping to [0, 1).

Used by examples/mca_tic_nicr_bending/run_study.py and examples/mca_porous_zirconia/run_study.py.
Written by hand: numpy's MT19937 is the 32-bit generator, and the standard library has neither.
"""

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
