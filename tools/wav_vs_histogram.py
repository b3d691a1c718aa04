#!/usr/bin/env python3
"""Counts how many of the metrics in `diffray ir` sidecars agree between the energy histograms (`bands`)
and the synthesized WAV (`bands_from_wav`) within one just-noticeable difference of ISO 3382-1 Table A.1:
T20, T30 and EDT 5 % (relative), C50 and C80 1 dB, D50 0.05, Ts 10 ms. Prints each sidecar's count and
the figures outside, then the total. Figures outside that the WAV's metrics flag as within their band
filter's reach (`filter_limited`: the analysis filter alone biases them beyond one JND) are marked and
counted apart.

Usage: tools/wav_vs_histogram.py SIDECAR.json [SIDECAR.json ...]
"""
import json
import sys

JND = {'t20': ('rel', 0.05), 't30': ('rel', 0.05), 'edt': ('rel', 0.05),
       'c50': ('abs', 1.0), 'c80': ('abs', 1.0), 'd50': ('abs', 0.05), 'ts': ('abs', 0.010)}


def compare(path):
    with open(path) as f:
        sidecar = json.load(f)
    figures, within, outside, limited = 0, 0, [], 0
    for listener in sidecar['listeners']:
        for band, hist in listener['bands'].items():
            wav = listener['bands_from_wav'][band]
            for name, (kind, jnd) in JND.items():
                a, b = hist.get(name), wav.get(name)
                if a is None or b is None:  # not measurable (too short a decay range)
                    continue
                figures += 1
                diff = (b - a) / a if kind == 'rel' else b - a
                if abs(diff) <= jnd:
                    within += 1
                else:
                    flag = name in wav.get('filter_limited', [])
                    limited += flag
                    outside.append(f"{listener['name']} {band} Hz {name}: histogram {a:.4g}, WAV {b:.4g}"
                                   + (" [filter-limited]" if flag else ""))
    return figures, within, outside, limited


def main():
    if len(sys.argv) < 2:
        sys.exit(__doc__.strip())
    total = within_total = limited_total = 0
    for path in sys.argv[1:]:
        try:
            figures, within, outside, limited = compare(path)
        except (OSError, ValueError, KeyError) as e:
            sys.exit(f"{path}: not a diffray ir sidecar ({e})")
        total += figures
        within_total += within
        limited_total += limited
        print(f"{path}: {within} of {figures} within one JND ({limited} of the others filter-limited)")
        for line in outside:
            print(f"  outside: {line}")
    print(f"total: {within_total} of {total} within one JND "
          f"({limited_total} of the {total - within_total} others filter-limited)")


if __name__ == '__main__':
    main()
