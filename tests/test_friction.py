"""Coulomb friction (anvilwave.anvil_rom.contact.coulomb_friction): the return mapping, and a
block on a rough floor pulled by a spring whose end follows a prescribed ramp-hold motion,
against its closed-form stick and slip phases and dissipated energy."""

from __future__ import annotations

import numpy as np
import pytest

from anvilwave.anvil_rom.contact import coulomb_friction

MASS, SPRING, MU, GRAVITY = 2.0, 200.0, 0.3, 9.81  # [kg], [N/m], [-], [m/s^2]
OMEGA = np.sqrt(SPRING / MASS)  # [rad/s]
CAP = MU * MASS * GRAVITY  # the Coulomb limit mu N [N]
# the spring end: forward at 0.3 m/s for 0.2 s, hold 0.6 s, back at 0.3 m/s for 0.25 s, hold
PHASES = ((0.3, 0.2), (0.0, 0.6), (-0.3, 0.25), (0.0, 0.6))  # (velocity [m/s], duration [s])


def test_return_mapping_sticks_inside_the_cone_and_slides_on_it():
    assert coulomb_friction(1.0, 1e-3, 100.0, 0.2, 1e4) == (11.0, 0.0)  # stick: 1 + 1e4 ds
    force, lost = coulomb_friction(15.0, 1e-3, 100.0, 0.2, 1e4)  # trial 25 > 20: slip
    assert force == 20.0 and lost == pytest.approx(20.0 * 5e-4)  # mu N x the slip 5e-4 m
    force, lost = coulomb_friction(-15.0, -1e-3, 100.0, 0.2, 1e4)  # the same, mirrored
    assert force == -20.0 and lost == pytest.approx(20.0 * 5e-4)
    # an opening pair (F_n <= 0) sheds its force and the spring's whole stored energy
    force, lost = coulomb_friction(15.0, 0.0, -5.0, 0.2, 1e4)
    assert force == 0.0 and lost == pytest.approx(15.0**2 / 2e4)


def closed_form_block():
    """Spring-end position and the block's slip, phase by phase, in closed form.

    Stuck with spring force F (|F| <= mu N), the block stays until the ramping end brings F to
    +-mu N; it then slides with y = X - x -+ mu N / k obeying y'' = -omega^2 y from y = 0,
    y' = V: x' = V (1 - cos omega t). Once the end stops, the block goes on sliding in the same
    direction about X -+ mu N / k and stops half an oscillation later (x' = 0), where it sticks
    if the spring force there lies inside the cone (checked). Returns the total slip path
    [m] and the times at which the block stops for good in each push [s].
    """
    x = X = t = 0.0
    path, stops = 0.0, []
    phases = list(PHASES)
    while phases:
        v_end, duration = phases.pop(0)
        force = SPRING * (X - x)
        if v_end == 0.0:
            X, t = X, t + duration
            continue
        sign = np.sign(v_end)
        t_stick = (sign * CAP - force) / (SPRING * v_end)
        assert 0.0 <= t_stick < duration, "the push must break the block loose"
        tau = duration - t_stick
        dx = v_end * tau - v_end / OMEGA * np.sin(OMEGA * tau)
        vel = v_end * (1.0 - np.cos(OMEGA * tau))
        x += dx
        X += v_end * duration
        t += duration
        # free slide after the end stops: y = X - x - sign mu N / k, y' = -x'
        y = X - x - sign * CAP / SPRING
        amplitude = np.hypot(y, vel / OMEGA)
        phase = np.arctan2(vel / OMEGA, y)  # y = A cos(omega s + phase)
        s_stop = (np.pi - phase) / OMEGA if sign > 0 else (-phase) / OMEGA
        s_stop = s_stop % (2.0 * np.pi / OMEGA)
        x_stop = X - sign * CAP / SPRING + sign * amplitude
        hold = phases[0][1]
        assert phases[0][0] == 0.0 and s_stop < hold, "the block must stop during the hold"
        assert abs(SPRING * (X - x_stop)) <= CAP, "the block must stick where it stops"
        path += abs(x_stop - x) + abs(dx)
        x = x_stop
        stops.append(t + s_stop)
    return path, stops


def simulate_block(time_step, tangential_stiffness):
    """Central differences on the block with the friction force from the return mapping."""
    n_steps = int(round(sum(d for _, d in PHASES) / time_step))
    edges = np.cumsum([0.0] + [d for _, d in PHASES])
    offsets = np.concatenate([[0.0], np.cumsum([v * d for v, d in PHASES])])
    x = v = force = dissipated = 0.0
    lost_per_step = np.zeros(n_steps)
    for n in range(n_steps):
        t = n * time_step
        k = min(np.searchsorted(edges, t, side="right") - 1, len(PHASES) - 1)
        X = offsets[k] + PHASES[k][0] * (t - edges[k])
        v += time_step / MASS * (SPRING * (X - x) - force)
        dx = time_step * v
        x += dx
        force, lost = coulomb_friction(force, dx, MASS * GRAVITY, MU, tangential_stiffness)
        dissipated += lost
        lost_per_step[n] = lost
    return dissipated, lost_per_step


def test_block_dissipates_mu_n_times_its_slip_path():
    path, stops = closed_form_block()
    exact = CAP * path
    assert len(stops) == 2 and exact > 0.0
    # the stick spring k_t is the law's only regularisation: it lets the stuck block move by
    # T / k_t and ring at omega_t = sqrt(k_t / m). Raise k_t by decades, the step following
    # at h omega_t = 0.5 (a quarter of the explicit limit 2): the dissipated energy converges
    # to the closed form, measured errors 2.2e-2, 1.4e-3, 2.0e-4, 2.1e-5 (k_t / k = 1e2..1e5)
    errors = []
    for ratio in (1e2, 1e3, 1e4, 1e5):
        kt = ratio * SPRING
        h = 0.5 / np.sqrt(kt / MASS)
        dissipated, lost = simulate_block(h, kt)
        errors.append(abs(dissipated / exact - 1.0))
        if ratio >= 1e3:
            t = np.arange(len(lost)) * h
            # it sticks before the first push breaks it loose, and after each stop but for
            # the micro-slips of the stick spring's ringing (< 0.1 % of the energy)
            assert not lost[t < 0.9 * CAP / (SPRING * PHASES[0][0])].any()
            for t_stop in stops:
                assert lost[(t > t_stop + 0.02) & (t < t_stop + 0.3)].sum() < 1e-3 * exact
    # the bar, 1 %, from k_t = 1e3 k on; then at least 3x better per decade
    assert errors[1] < 0.01, errors
    assert np.all(np.array(errors[1:]) < np.array(errors[:-1]) / 3.0), errors


def test_block_dissipation_is_converged_in_the_step():
    """At a fixed stick spring (1e4 k) the step alone changes the dissipated energy by less
    than 1e-4 (halving it twice from h omega_t = 0.5); measured 4.7e-5."""
    kt = 1e4 * SPRING
    omega_t = np.sqrt(kt / MASS)
    values = [simulate_block(f / omega_t, kt)[0] for f in (0.5, 0.25, 0.125)]
    assert np.ptp(values) < 1e-4 * values[-1], values
