"""The colour targets (issue 14): what a film of whole blood over a stated mucosa colour looks like,
computed here from the sourced coefficients alone, in NumPy and double precision, against what the
blend draws (tests/effects/optics_probe.cpp), within ΔE2000 ≤ 2.

The computation, written from its sources and not from bleedsim's code:
- sRGB bytes to linear light and back: IEC 61966-2-1.
- Whole blood's absorption at 650, 550 and 450 nm for red, green and blue: μa = 2.303 · ε · c with ε
  haemoglobin's molar extinction coefficient (S. Prahl, omlc.org/spectra/hemoglobin, compiled from
  W. B. Gratzer and N. Kollias) mixed by the oxygen saturation, and c = 150 g/L / 64,500 g/mol.
- Beer–Lambert down through the film to the tissue and back up: exp(−2 · μa · h).
- ΔE2000 (G. Sharma, W. Wu, E. N. Dalal, Color Res. Appl. 30 (2005) 21–30) between the two colours in
  CIE L*a*b* (D65 white), through sRGB's XYZ matrix.
Arterial blood is taken at 98 % saturation, venous at 75 %.
"""
import argparse
import subprocess
import sys

import numpy as np

MUCOSA = (202, 113, 113)  # the flat pink the procedural mucosa shows
SATURATIONS = {"arterial": 0.98, "venous": 0.75}
THICKNESSES_MM = (0.05, 0.1, 0.5, 1.0)
EPSILON = {  # cm⁻¹/M: (HbO2, Hb) at 650, 550, 450 nm
    650: (368.0, 3750.12),
    550: (43016.0, 53412.0),
    450: (62816.0, 103292.0),
}
MOLAR = 150.0 / 64500.0  # mol/L


def srgb_to_linear(c):
    c = np.asarray(c, dtype=np.float64) / 255.0
    return np.where(c <= 0.04045, c / 12.92, ((c + 0.055) / 1.055) ** 2.4)


def linear_to_srgb_byte(v):
    v = np.clip(np.asarray(v, dtype=np.float64), 0.0, 1.0)
    c = np.where(v <= 0.0031308, 12.92 * v, 1.055 * v ** (1 / 2.4) - 0.055)
    return np.floor(c * 255.0 + 0.5)


def absorption_per_mm(saturation):
    return np.array([2.303 * (saturation * o + (1 - saturation) * d) * MOLAR / 10.0
                     for o, d in (EPSILON[650], EPSILON[550], EPSILON[450])])


def lab(rgb_bytes):
    linear = srgb_to_linear(rgb_bytes)
    m = np.array([[0.4124564, 0.3575761, 0.1804375],
                  [0.2126729, 0.7151522, 0.0721750],
                  [0.0193339, 0.1191920, 0.9503041]])
    xyz = m @ linear / np.array([0.95047, 1.0, 1.08883])
    f = np.where(xyz > (6 / 29) ** 3, np.cbrt(xyz), xyz / (3 * (6 / 29) ** 2) + 4 / 29)
    return np.array([116 * f[1] - 16, 500 * (f[0] - f[1]), 200 * (f[1] - f[2])])


def delta_e2000(lab1, lab2):
    L1, a1, b1 = lab1
    L2, a2, b2 = lab2
    C1, C2 = np.hypot(a1, b1), np.hypot(a2, b2)
    Cbar = (C1 + C2) / 2
    G = 0.5 * (1 - np.sqrt(Cbar ** 7 / (Cbar ** 7 + 25.0 ** 7)))
    a1p, a2p = (1 + G) * a1, (1 + G) * a2
    C1p, C2p = np.hypot(a1p, b1), np.hypot(a2p, b2)
    h1p = np.degrees(np.arctan2(b1, a1p)) % 360
    h2p = np.degrees(np.arctan2(b2, a2p)) % 360
    dLp, dCp = L2 - L1, C2p - C1p
    dhp = 0.0 if C1p * C2p == 0 else (h2p - h1p if abs(h2p - h1p) <= 180 else
                                       h2p - h1p - 360 if h2p - h1p > 180 else h2p - h1p + 360)
    dHp = 2 * np.sqrt(C1p * C2p) * np.sin(np.radians(dhp) / 2)
    Lbarp, Cbarp = (L1 + L2) / 2, (C1p + C2p) / 2
    if C1p * C2p == 0:
        hbarp = h1p + h2p
    elif abs(h1p - h2p) <= 180:
        hbarp = (h1p + h2p) / 2
    else:
        hbarp = (h1p + h2p + 360) / 2 if h1p + h2p < 360 else (h1p + h2p - 360) / 2
    T = (1 - 0.17 * np.cos(np.radians(hbarp - 30)) + 0.24 * np.cos(np.radians(2 * hbarp))
         + 0.32 * np.cos(np.radians(3 * hbarp + 6)) - 0.20 * np.cos(np.radians(4 * hbarp - 63)))
    dtheta = 30 * np.exp(-(((hbarp - 275) / 25) ** 2))
    RC = 2 * np.sqrt(Cbarp ** 7 / (Cbarp ** 7 + 25.0 ** 7))
    SL = 1 + 0.015 * (Lbarp - 50) ** 2 / np.sqrt(20 + (Lbarp - 50) ** 2)
    SC, SH = 1 + 0.045 * Cbarp, 1 + 0.015 * Cbarp * T
    RT = -np.sin(np.radians(2 * dtheta)) * RC
    return np.sqrt((dLp / SL) ** 2 + (dCp / SC) ** 2 + (dHp / SH) ** 2 + RT * (dCp / SC) * (dHp / SH))


def self_check():
    """Sharma et al.'s test pairs 1 and 17: ΔE2000 2.0425 and 27.1492."""
    for l1, l2, want in (((50.0, 2.6772, -79.7751), (50.0, 0.0, -82.7485), 2.0425),
                         ((50.0, 2.5, 0.0), (73.0, 25.0, -18.0), 27.1492)):
        got = delta_e2000(np.array(l1), np.array(l2))
        if abs(got - want) > 1e-4:
            sys.exit(f"FAIL ΔE2000 self-check: {got:.4f}, Sharma et al. give {want}")


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("--probe", required=True)
    args = parser.parse_args()
    self_check()
    command = [args.probe, *map(str, MUCOSA), *map(str, SATURATIONS.values()), "--", *map(str, THICKNESSES_MM)]
    drawn = {}
    for line in subprocess.run(command, capture_output=True, text=True, check=True).stdout.split("\n"):
        if line.strip():
            s, h, r, g, b = line.split()
            drawn[(float(s), float(h))] = np.array([int(r), int(g), int(b)])
    worst, failures = 0.0, []
    for name, s in SATURATIONS.items():
        for h in THICKNESSES_MM:
            expected = linear_to_srgb_byte(srgb_to_linear(MUCOSA) * np.exp(-2 * absorption_per_mm(s) * h))
            got = drawn[(s, h)]
            de = delta_e2000(lab(expected), lab(got))
            worst = max(worst, de)
            print(f"{name:8s} {h:4.2f} mm over {MUCOSA}: expected {tuple(int(v) for v in expected)}, "
                  f"drawn {tuple(int(v) for v in got)}, ΔE2000 {de:.3f}")
            if de > 2.0:
                failures.append(f"{name} {h} mm: ΔE2000 {de:.3f} > 2")
    if failures:
        sys.exit("FAIL " + "; ".join(failures))
    print(f"ok: {len(SATURATIONS) * len(THICKNESSES_MM)} colours within ΔE2000 ≤ 2 (worst {worst:.3f})")


if __name__ == "__main__":
    main()
