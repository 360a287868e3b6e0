"""Rest's invariants in a golden scene's key frames (docs/particles.md#rest), from the scenario alone."""

import numpy as np

BEING_BORN = 2**32 - 1   # a film with depth's parcel being born (core/physics/particle_state.h, kBeingBorn)
JOINING = 2**31          # ... joining after a birth that ran out crowded, + the steps since (kJoining)


def check_rest(settings, k, live, age, rest, position, anchor, velocity, problems):
    """Rest's invariants (docs/particles.md#rest) at key frame k, over the live slots: a step that left
    a particle more than the rest distance from its anchor moved the anchor to it and zeroed its
    count, so each is within the distance of its anchor (float32's rounding of the distance
    allowed) and at it when its count is 0; the count rises at most one a step from 0 at its birth
    and stops at the rest steps; a sleeper, at the rest steps, has no speed at all. A film with
    depth's births and joining parcels keep no rest: their words are only where film_depth is, a
    joining parcel's count since it joined below the join steps and no more than its age."""
    rest, steps = rest[live].astype(np.int64), settings["rest_steps"]
    born, joining = rest == BEING_BORN, (rest >= JOINING) & (rest != BEING_BORN)
    unknown = (born | joining) & (not settings["film_depth"])
    joined_too_long = joining & ((rest - JOINING >= settings["join_steps"]) | (rest - JOINING > age[live]))
    resting = ~(born | joining)
    p, a, v = position[live].astype(np.float64), anchor[live].astype(np.float64), velocity[live]
    away = np.hypot(*(p - a).T)
    far = resting & (away > settings["rest_distance"] * (1 + 1e-6) + np.spacing(np.float32(np.abs(p).max(initial=1))))
    moved = (rest == 0) & (away != 0)
    counted = resting & (rest > np.minimum(age[live], steps))
    awake_still = (steps > 0) & (rest == steps) & (v != 0).any(axis=1)
    for what, bad in [("with a birth's rest word in a scene without film_depth", unknown),
                      ("joining the film for longer than the join steps or than they lived", joined_too_long),
                      ("further than the rest distance from their anchor", far),
                      ("at a count of 0 away from their anchor", moved),
                      ("counted at rest longer than they lived or past the rest steps", counted),
                      ("asleep with a speed", awake_still)]:
        if bad.any():
            s = np.flatnonzero(live)[np.flatnonzero(bad)[0]]
            problems.append(f"key frame {k}: {bad.sum()} live particles {what} (slot {s}: rest {rest[bad][0]}, "
                            f"at {tuple(position[s])}, anchor {tuple(anchor[s])})")
