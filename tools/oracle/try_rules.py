#!/usr/bin/env python3
"""Stopping rules tried offline (issue #59) on `penumbra-oracle --checkpoints FILE` data: each
checkpoint of a reference run (no stop, no tile skipped) with the rule's estimate and the true
error against the 1024-frame image. For each rule, where each view would stop and that over its
oracle frame. A tool for choosing a rule, not the rule: the renderer's is
renderer/src/progressive/convergence.cpp, and penumbra-oracle measures it as users get it.

  tools/oracle/try_rules.py FILE.tsv [--cap 1024]
"""
import argparse
import collections
import math

ROUNDING = 1.0 / 6.0   # two roundings to 8 bits, in steps squared
MARGIN = 1.0           # convergence.h kChangeMargin, inside the recorded estimates (1.1 before 2026-12-07's second round)


def raw(displayed, frame, cap):
    """The scaled change behind a displayed estimate (displayedError inverted)."""
    rest = math.sqrt(max(0.0, 1.0 - frame / cap))
    return math.sqrt(max(displayed * displayed - ROUNDING, 0.0)) / (MARGIN * max(rest, 1e-9))


def shown(change, frame, cap, margin):
    rest = math.sqrt(max(0.0, 1.0 - frame / cap))
    e = margin * change * rest
    return math.sqrt(e * e + ROUNDING)


def slope(points):
    """-d log(value) / d log(frame), least squares."""
    pts = [(math.log(f), math.log(v)) for f, v in points if v > 0]
    if len(pts) < 2:
        return None
    n = len(pts)
    sx = sum(p[0] for p in pts)
    sy = sum(p[1] for p in pts)
    sxx = sum(p[0] ** 2 for p in pts)
    sxy = sum(p[0] * p[1] for p in pts)
    den = n * sxx - sx * sx
    return None if den <= 1e-12 else -(n * sxy - sx * sy) / den


def load(path):
    views = collections.OrderedDict()
    for line in open(path):
        f = line.rstrip('\n').split('\t')
        if len(f) < 9:
            continue
        name, oracle, ref_cap, frame = f[0], int(f[1]), int(f[2]), int(f[3])
        est, tile, decay, true_rms, true_tile = map(float, f[4:9])
        v = views.setdefault(name, {'oracle': oracle, 'points': []})
        v['points'].append({'frame': frame, 'rms': raw(est, frame, ref_cap),
                            'tile': raw(tile, frame, ref_cap), 'decay': decay,
                            'true_rms': true_rms, 'true_tile': true_tile})
    return views


def stop(view, cap, margin_of, in_a_row=1):
    """The first checkpoint after `in_a_row` in a row whose estimate meets the criterion."""
    history, run = [], 0
    for p in view['points']:
        history.append(p)
        m = margin_of(history)
        ok = shown(p['rms'], p['frame'], cap, m) < 1.0 and shown(p['tile'], p['frame'], cap, m) < 3.0
        run = run + 1 if ok else 0
        if run >= in_a_row:
            return p['frame']
    return cap


def constant(m):
    return lambda history: m


def by_rate(low, high, window=8):
    """A margin from how the tiles' estimate falls: noise (rate 1/2) keeps `low`'s meaning at
    rate 1/2; a rate towards 1 (stratified, low-discrepancy terms, whose change from N/2
    overstates) lowers it, a rate under 1/2 (a slow drift the change understates) raises it,
    linearly between (0.25, high) and (1, low)."""
    def margin(history):
        pts = [(p['frame'], p['tile']) for p in history[-window:]]
        a = slope(pts)
        if a is None or len(pts) < 4:
            return (low + high) / 2
        a = min(1.0, max(0.25, a))
        return high + (low - high) * (a - 0.25) / 0.75
    return margin


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument('tsv')
    ap.add_argument('--cap', type=int, default=1024)
    a = ap.parse_args()
    views = load(a.tsv)
    rules = [('margin %.1f' % m, constant(m), 1) for m in (0.9, 1.0, 1.1, 1.2)]
    rules += [('margin %.1f, two checkpoints in a row' % m, constant(m), 2) for m in (0.9, 1.0)]
    for low, high in [(0.8, 1.4), (0.9, 1.3)]:
        rules.append(('margin by the tiles\' rate, %.1f..%.1f' % (low, high), by_rate(low, high), 1))
    # How far each view's estimate is from its truth near its oracle frame: what a margin
    # would have to be, per view.
    print('| view | oracle frame | true / estimated error, RMS and tiles, at the checkpoints '
          'from 0.7x to 1.4x the oracle frame |')
    print('|---|---|---|')
    for name, v in views.items():
        cells = []
        for p in v['points']:
            if 0.7 * v['oracle'] <= p['frame'] <= 1.4 * v['oracle']:
                rest = math.sqrt(max(0.0, 1.0 - p['frame'] / a.cap))
                t = [math.sqrt(max(x * x - ROUNDING, 1e-6)) for x in (p['true_rms'], p['true_tile'])]
                cells.append('%d: %.2f / %.2f' % (p['frame'], t[0] / max(p['rms'] * rest, 1e-6),
                                                 t[1] / max(p['tile'] * rest, 1e-6)))
        print('| %s | %d | %s |' % (name, v['oracle'], ', '.join(cells)))
    print()
    print('| rule | ' + ' | '.join(views) + ' | in [1.0, 1.3] |')
    print('|---' * (len(views) + 2) + '|')
    for name, rule, in_a_row in rules:
        cells, inside = [], 0
        for v in views.values():
            s = stop(v, a.cap, rule, in_a_row)
            r = s / v['oracle'] if v['oracle'] > 0 else float('nan')
            inside += 1.0 <= r <= 1.3
            cells.append('%d (%.2f)' % (s, r))
        print('| %s | %s | %d / %d |' % (name, ' | '.join(cells), inside, len(views)))


if __name__ == '__main__':
    main()
