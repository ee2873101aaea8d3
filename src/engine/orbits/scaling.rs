//! Power laws of the (2, 2k) branch near the period-doubling point (paper's Fig. 4, 5).
