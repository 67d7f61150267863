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
