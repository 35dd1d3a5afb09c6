"""Au's law checked against a Monte Carlo of identified simulated records (SI).

``python -m hubvib.identification.montecarlo [--records N] [--out FILE.md]`` simulates
records of one mode (:mod:`.records`), identifies each with :mod:`.bfft` and
writes a markdown table of the scatter of the identified frequencies against
Au's closed form and the method's Cramer-Rao bound (docs/diagnosis.md quotes it).
"""
from __future__ import annotations

import argparse
import math
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from .bfft import identify_mode
from .law import au_sigma_hz, fisher_sigma_hz
from .records import simulate

#: the reference case: Raba 118/76 mode 13 (4548 Hz), 10 s records
CASES = ((4548.0, 0.01, 10.0), (4548.0, 0.02, 10.0), (4548.0, 0.05, 10.0),
         (4548.0, 0.02, 60.0))
SNR = 100.0


@dataclass(frozen=True)
class Scatter:
    """Scatter of frequencies identified from ``records`` simulated records.

    Attributes
    ----------
    frequency_hz, damping_ratio, record_s, snr : float
        The simulated mode [Hz], [-], record length [s], modal SNR [-].
    records : int
    bias_hz, std_hz : float
        Mean error and sample standard deviation of the identified frequency [Hz].
    au_hz, fisher_hz : float
        Au's closed form and the Cramer-Rao bound of the method [Hz].
    """

    frequency_hz: float
    damping_ratio: float
    record_s: float
    snr: float
    records: int
    bias_hz: float
    std_hz: float
    au_hz: float
    fisher_hz: float

    @property
    def std_ci(self) -> tuple[float, float]:
        """Approximate 95 % interval of the sample standard deviation (normal theory) [Hz]."""
        half = 1.96 / math.sqrt(2 * (self.records - 1))
        return self.std_hz / (1 + half), self.std_hz / (1 - half)


def identified(frequency_hz: float, damping_ratio: float, record_s: float, snr: float,
               records: int, seed: int = 0) -> np.ndarray:
    """Frequencies [Hz] identified from ``records`` simulated records of one mode."""
    rng = np.random.default_rng(seed)
    rate = 4.4 * frequency_hz  # a few samples per period, band well below Nyquist
    return np.array([identify_mode(simulate(frequency_hz, damping_ratio, record_s, rate, snr,
                                            rng).values, rate, frequency_hz,
                                   damping_ratio).frequency_hz for _ in range(records)])


def scatter(frequency_hz: float, damping_ratio: float, record_s: float, snr: float = SNR,
            records: int = 200, seed: int = 0) -> Scatter:
    """Monte Carlo scatter of one case against the law."""
    f = identified(frequency_hz, damping_ratio, record_s, snr, records, seed)
    return Scatter(frequency_hz, damping_ratio, record_s, snr, records,
                   float(f.mean() - frequency_hz), float(f.std(ddof=1)),
                   float(au_sigma_hz(frequency_hz, damping_ratio, record_s)),
                   fisher_sigma_hz(frequency_hz, damping_ratio, record_s, snr))


def table(rows: list[Scatter]) -> list[str]:
    """Markdown table of Monte Carlo scatter against the law."""
    lines = ["| f [Hz] | damping [%] | T [s] | SNR | records | MC std [Hz] (95 % CI) | "
             "bias [Hz] | Cramer-Rao bound [Hz] | Au's law [Hz] |",
             "|---:|---:|---:|---:|---:|---:|---:|---:|---:|"]
    for r in rows:
        low, high = r.std_ci
        lines.append(f"| {r.frequency_hz:g} | {100 * r.damping_ratio:g} | {r.record_s:g} | "
                     f"{r.snr:g} | {r.records} | {r.std_hz:.3g} ({low:.3g}..{high:.3g}) | "
                     f"{r.bias_hz:+.2g} | {r.fisher_hz:.3g} | {r.au_hz:.3g} |")
    return lines


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--records", type=int, default=200)
    parser.add_argument("--out", type=Path)
    args = parser.parse_args(argv)
    text = "\n".join(table([scatter(f, z, T, records=args.records) for f, z, T in CASES]))
    if args.out:
        args.out.write_text(text + "\n", encoding="utf-8")
    print(text)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
