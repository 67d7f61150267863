"""The real captures in data/ and what acquisition must find in each: PRN -> (Doppler in
Hz, code delay in samples), as found in the captures and confirmed by their fixes."""

EXPECTED_ACQUISITIONS = {
    "L1_20211202_084700_4MHz_IQ": {31: (-190, 1159), 26: (650, 3599), 29: (-2220, 1653), 16: (2600, 3958),
                                   32: (-3380, 2766)},
    "L1_20211125_004000_12MHz_I": {5: (140, 5611), 13: (-230, 6004), 20: (-1370, 8172), 15: (1730, 9317),
                                   2: (-2740, 5328), 30: (-1880, 4719), 11: (-3280, 11004), 18: (3280, 6580),
                                   29: (-2030, 9075)},
}
DOPPLER_TOLERANCE_HZ = 250
DELAY_TOLERANCE_SAMPLES = 2

# Galileo E1 in the same captures: SVID -> (Doppler in Hz, code delay in samples within the
# 4 ms code period), as GNSS-SDR 0.0.17's Galileo_E1_PCPS_Ambiguous_Acquisition (4 ms, five
# dwells) finds them; every one is also found by `deepnav acquire --systems galileo` in
# successive 20 ms windows with the code drift its Doppler implies
# (results/galileo_acquisition/README.md). GNSS-SDR's Doppler bin is 125 Hz and its delays
# whole samples.
EXPECTED_GALILEO_ACQUISITIONS = {
    "L1_20211202_084700_4MHz_IQ": {7: (-2375, 11297), 15: (2875, 5882), 19: (2125, 10165), 20: (1250, 2047),
                                   21: (2000, 13425), 27: (500, 4509), 30: (-1375, 7689)},
    "L1_20211125_004000_12MHz_I": {2: (2875, 23153), 3: (-1000, 30327), 5: (-1875, 39663), 7: (2290, 29730),
                                   8: (1000, 44692), 13: (1125, 35459), 15: (-1750, 18790), 25: (2000, 4523)},
}
GALILEO_DOPPLER_TOLERANCE_HZ = 125
