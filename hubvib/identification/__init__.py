"""Natural frequencies identified from vibration records, and how uncertain they are (SI).

``law`` (Au's uncertainty law and the Cramer-Rao bound of the shipped method),
``records`` (simulated ambient records of known modes), ``bfft`` (single-mode
Bayesian-FFT / Whittle identification of a frequency from one record) and
``montecarlo`` (the law checked against identified simulated records).  numpy
and scipy only.
"""
