"""Analysis of perversions along a bistrip path (thesis ch. 3, §3.4), shared by sweep.py and
tests: perversions tracked between outputs and their events (annihilation, coalescence,
creation), the winding of a perversion about the end-to-end axis, the energy condensation at
each perversion, and whether a final shape is a helix or a V.

Inputs are plain numbers (positions in mm along the reference strip, centreline samples), so
that the functions can be checked on constructed data (tests/bistrip_perversions.py).
"""
import numpy as np

# Helix against V (fig3.10), measured on the default run (w = 5, nz = 100):
# once helices have formed (end distance <= 240 mm) its frame turns 3.0 to 5.7 times
# (int |twist| ds / 2 pi) and its centreline's lateral spread ratio is 0.81 to 0.99; the
# planar buckle just before (250 mm) has 0.15 turns and ratio 0.07. The thresholds sit
# between, a factor of 3 or more from either side's measured value.
HELIX_MIN_FRAME_TURNS = 1.0
HELIX_MIN_LATERAL_RATIO = 0.3
# Buckled at all: the same run's centreline strays at most 0.09 mm from its mean axis while
# straight (256 mm, the seeded imperfection grown), 0.63 mm at the onset (250 mm) and 3 to 5 mm
# as helices; below 0.3 mm the strip is "straight" (not yet a helix nor a V)
STRAIGHT_MAX_LATERAL = 0.3


def match(before, after, tolerance):
    """Pairs (i, j) of perversions at positions before[i] and after[j] (each sorted) that are
    the same perversion one output later. Perversions cannot pass through one another, so the
    pairing keeps their order; among such pairings it is the one of least cost, where a pair
    costs its displacement (at most `tolerance`) and a perversion left unpaired (vanished or
    appeared) costs `tolerance`: pairing is preferred whenever it moves less than that."""
    n, m = len(before), len(after)
    cost = np.full((n + 1, m + 1), np.inf)
    cost[0, :] = tolerance * np.arange(m + 1)
    cost[:, 0] = tolerance * np.arange(n + 1)
    for i in range(1, n + 1):
        for j in range(1, m + 1):
            moved = abs(before[i - 1] - after[j - 1])
            cost[i, j] = min(cost[i - 1, j] + tolerance, cost[i, j - 1] + tolerance,
                             cost[i - 1, j - 1] + moved if moved <= tolerance else np.inf)
    pairs, i, j = [], n, m
    while i and j:
        moved = abs(before[i - 1] - after[j - 1])
        if moved <= tolerance and np.isclose(cost[i, j], cost[i - 1, j - 1] + moved):
            pairs.append((i - 1, j - 1))
            i, j = i - 1, j - 1
        elif np.isclose(cost[i, j], cost[i - 1, j] + tolerance):
            i -= 1
        else:
            j -= 1
    return pairs[::-1]


def runs(indices):
    """Consecutive runs of sorted integers: [1, 2, 5] -> [[1, 2], [5]]."""
    grouped = []
    for i in indices:
        if grouped and i == grouped[-1][-1] + 1:
            grouped[-1].append(i)
        else:
            grouped.append([i])
    return grouped


def events(before, after, pairs, near):
    """What happened between two outputs, as dicts {kind, positions, survivor}.

    Neighbouring perversions have opposite chirality changes, so they vanish and appear in
    pairs. A run of neighbours that vanished is split into pairs, each
    - "coalescence" (3 -> 1, Fig. 3.8b) if a neighbour in the run's order survived within
      `near` of the pair (the thesis sees coalescence only within about two helical periods),
    - "annihilation" (2 -> 0) otherwise;
    a run of neighbours that appeared gives "creation" pairs. An odd one out is "vanishing"
    or "appearance" (a perversion leaving or entering at a clamp, or one moved further than
    the matching tolerance)."""
    kept_before = {i for i, _ in pairs}
    kept_after = {j for _, j in pairs}
    found = []
    for run in runs([i for i in range(len(before)) if i not in kept_before]):
        neighbours = [k for k in (run[0] - 1, run[-1] + 1) if k in kept_before]
        for first in range(0, len(run) - 1, 2):
            pair = [before[run[first]], before[run[first + 1]]]
            gaps = [(min(abs(before[k] - z) for z in pair), before[k]) for k in neighbours]
            gap, survivor = min(gaps) if gaps else (np.inf, None)
            found.append({"kind": "coalescence" if gap <= near else "annihilation",
                          "positions": pair, "survivor": survivor if gap <= near else None})
        if len(run) % 2:
            found.append({"kind": "vanishing", "positions": [before[run[-1]]],
                          "survivor": None})
    for run in runs([j for j in range(len(after)) if j not in kept_after]):
        for first in range(0, len(run) - 1, 2):
            found.append({"kind": "creation", "positions": [after[run[first]],
                                                            after[run[first + 1]]],
                          "survivor": None})
        if len(run) % 2:
            found.append({"kind": "appearance", "positions": [after[run[-1]]],
                          "survivor": None})
    return found


def track(path, tolerance, near):
    """Identities and events along a path: `path` is a list of position lists (one per
    output, each sorted), `near` a number or a list of one per output. Returns (ids, found):
    ids[k][n] identifies perversion n of output k (the same id for a matched perversion),
    found lists the events of each step k-1 -> k, each with "output": k."""
    ids, found, next_id = [], [], 0
    for k, positions in enumerate(path):
        current = [None] * len(positions)
        if k:
            pairs = match(path[k - 1], positions, tolerance)
            for i, j in pairs:
                current[j] = ids[k - 1][i]
            reach = near[k] if np.ndim(near) else near
            found += [dict(e, output=k) for e in events(path[k - 1], positions, pairs, reach)]
        for j in range(len(current)):
            if current[j] is None:
                current[j], next_id = next_id, next_id + 1
        ids.append(current)
    return ids, found


def frame_angle(Z, width, at):
    """The angle (rad) about the end-to-end axis z of the width vector d1 at reference
    position `at`, d1 interpolated linearly between the samples Z (its xy projection)."""
    width = np.asarray(width)
    return np.arctan2(np.interp(at, Z, width[:, 1]), np.interp(at, Z, width[:, 0]))


def windings(ids, angles):
    """Each perversion's winding (degrees) over the outputs, unwrapped: {id: array over the
    outputs, nan where it does not exist}. angles[k][n] is perversion n's frame angle (rad) at
    output k; consecutive outputs must turn it by less than half a turn."""
    turned = {}
    for k, (output_ids, output_angles) in enumerate(zip(ids, angles)):
        for i, angle in zip(output_ids, output_angles):
            turned.setdefault(i, np.full(len(ids), np.nan))[k] = angle
    for i, angle in turned.items():
        there = ~np.isnan(angle)
        angle[there] = np.degrees(np.unwrap(angle[there]))
    return turned


def mirror_asymmetry(positions, L):
    """How far the outer perversions are from mirror images about z = L/2: first + last - L
    (mm; 0 when mirror-symmetric), nan with fewer than two."""
    return positions[0] + positions[-1] - L if len(positions) > 1 else np.nan


def condensation(z, scaled, positions, L, clamp_zone, far):
    """The energy condensation at each perversion of one output from the slab profile E~(z)
    (slab centres z, sorted):
    - peaks: per perversion its peak of E~, searched between the midpoints to its neighbours
      (the clamp zones excluded: their boundary layers hold more energy still), its position
      and width (mm: the contiguous slabs above half the peak);
    - troughs: the least E~ between each two neighbouring peaks: raised above the background
      where the perversions repel (Fig. 3.7b, green arrow);
    - background: the median E~ over slabs at least `far` from every perversion and outside
      the clamp zones (nan if there are none)."""
    z, scaled = np.asarray(z), np.asarray(scaled)
    if not positions:
        return [], [], float(np.median(scaled[(z >= clamp_zone) & (z <= L - clamp_zone)]))
    slab = z[1] - z[0]
    inner = (z >= clamp_zone) & (z <= L - clamp_zone)
    bounds = [clamp_zone, *[(a + b) / 2 for a, b in zip(positions, positions[1:])],
              L - clamp_zone]
    peaks = []
    for lo, hi in zip(bounds, bounds[1:]):
        window = np.flatnonzero((z >= lo) & (z <= hi))
        if not len(window):
            peaks.append({"peak": np.nan, "at": np.nan, "width": np.nan})
            continue
        top = window[np.argmax(scaled[window])]
        first = last = top
        while first > window[0] and scaled[first - 1] >= scaled[top] / 2:
            first -= 1
        while last < window[-1] and scaled[last + 1] >= scaled[top] / 2:
            last += 1
        peaks.append({"peak": scaled[top], "at": z[top], "width": (last - first + 1) * slab})
    troughs = []
    for a, b in zip(peaks, peaks[1:]):
        between = (z >= a["at"]) & (z <= b["at"])
        troughs.append(scaled[between].min() if between.any() else np.nan)
    distant = inner & np.all(np.abs(z[:, None] - np.asarray(positions)[None, :]) >= far,
                             axis=1)
    background = float(np.median(scaled[distant])) if distant.any() else np.nan
    return peaks, troughs, background


def shape(points, twist):
    """Helix or V from a centreline: points (n x 3, along the strip) and the frame's twist per
    deformed arc length at each. Returns {frame_turns, lateral_ratio, shape}:
    - frame_turns = int |twist| ds / 2 pi: a helix's frame turns with it, a V's barely;
    - lateral_ratio: the smaller over the larger principal spread of the centreline about the
      end-to-end axis (its x, y): near 1 for a helix winding round the axis, near 0 for a
      planar V;
    - lateral: the largest distance (mm) of the centreline from its mean axis;
    - shape: "straight" when lateral is below STRAIGHT_MAX_LATERAL, else "helix/perversions"
      when frame_turns and lateral_ratio reach HELIX_MIN_FRAME_TURNS and
      HELIX_MIN_LATERAL_RATIO, else "V-shape"."""
    points = np.asarray(points)
    s = np.concatenate([[0], np.cumsum(np.linalg.norm(np.diff(points, axis=0), axis=1))])
    turns = float(np.trapz(np.abs(twist), s) / (2 * np.pi))
    lateral = points[:, :2] - points[:, :2].mean(axis=0)
    spread = np.linalg.svd(lateral, compute_uv=False)
    ratio = float(spread[1] / spread[0]) if spread[0] > 0 else 0.0
    largest = float(np.linalg.norm(lateral, axis=1).max())
    helix = turns >= HELIX_MIN_FRAME_TURNS and ratio >= HELIX_MIN_LATERAL_RATIO
    return {"frame_turns": turns, "lateral_ratio": ratio, "lateral": largest,
            "shape": ("straight" if largest < STRAIGHT_MAX_LATERAL
                      else "helix/perversions" if helix else "V-shape")}
