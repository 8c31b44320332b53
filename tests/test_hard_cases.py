"""The hard cases of issue 27 (docs/DESIGN.md "Hard cases"): contacts where today's coupled
solver (model/coupling.py, a force balance inside a deformation fixed point) fails.

Each case runs once, under a wall-clock budget (signal.alarm), on a small line mesh and with
the force balance limited to 20 iterations where that leaves the failure where it is but
makes it cost seconds instead of a minute (measured: docs/DESIGN.md "Hard cases"); a case
found on a 2-D mesh runs on it. Two
tests per case:

- what a user needs, strict xfail where it fails today: the run converges and says so;
- what must hold even today: the run ends within its budget, and when it does not converge
  it says where and why, and keeps what it computed (the series so far, converged = 0).
"""

import functools
import math
import re
import signal
import statistics
import time
from dataclasses import dataclass

import numpy as np
import pytest
import scipy.sparse as sp
from scipy.sparse.linalg import splu

import lubecontact as lc
from lubecontact.cli.transient import summary
from lubecontact.unsteady import integrator

TABLE1 = "config/scenes/table1.yaml"
BUDGET = 30  # s of wall clock per case; each measured at 0.5-17 s on the shared 2-core machine
# except cases that now converge and take longer: the 100 Pa s fretting runs to the end in
# 24-30 s (149 Newton steps with long line searches), and on the default 51-node line in 11 s
# of CPU alone (105 steps and a jump; 22 s with a monotone line search); the 1 Pa s fretting
# under 20 N runs in 15 s (191 steps, 5 jumps over impasses), the 10 Pa s one in 21-23 s (7
# jumps); their alarm still stops a run that hangs. The 20 N grease stop runs on its 2-D mesh
# for 83 s (its case below), a steady one-Newton point near lift-off by continuation in
# 22-26 s (its), Fig. 12's 2-D finish in 12.6-13.2 s alone, past 30 s once in CI, and the
# tight Bingham stop on the automatic domain in 20 s alone, before the grease step retry
# (integrator.grease_step_retry) took it on another path, 460 steps against 242: 40 against 24 s
# of CPU on the slower machine of machine_slowness below. There the Herschel-Bulkley stop took
# 25 s and its creep-1e8 twin's failure 11-15 s, and the connector grease at 0.003 m/s on 51 x 51
# 108 s where it had taken 1.7 s, and the 10 N point near lift-off 89 s alone (22-23 s before),
# past its stretched 60 s (111 s) and 90 s (130 s) beside another case in CI: a 150 s alarm;
# the 20 N grease stop took 220 s alone, past its stretched 150 s (216 s) in CI: 300 s. These
# two ran 2.5-4 times as long as on the faster machine where the factorisation took 1.4-2
# times as long: the stretch does not cover them alone. The 0.003 m/s point's cold start fails
# there and a continuation path reaches the point (the same code since the case converged,
# forty-sixth session): the path is as fragile as round-off. The Herschel-Bulkley stop at a
# creep of 1e8 Pa s took 11.6 s of CPU in the forty-seventh session (unit 0.223 s, 90 levels)
# and 30.4 s in the forty-eighth (unit 0.300 s, 92 levels), past its stretched 57 s beside
# another case in CI
LONGER_BUDGET = {"herschel_bulkley_stop_creep_1e8": 60,
                 "fretting_stiff_grease": 60, "fretting_stiff_grease_51_nodes": 60, "fretting_1_Pa_s_20_N_51_nodes": 60,
                 "fretting_10_Pa_s_20_N_51_nodes": 60, "grease_stop_20_N": 300,
                 "newton_10_N_0063": 150, "fig12_30_N_2d_finish": 60,
                 "bingham_stop_automatic_domain_tight": 60, "grease_2d_0_003_m_s": 90}
QUICK = {"mesh.ny": 1, "solver.max_iterations": 20}
# a Bingham grease stopped on the 31-node line of the automatic domain (its inlet of 1 m/s)
BINGHAM_AUTOMATIC = {"mesh.ny": 1, "mesh.nx": 31, "lubricant.rheology": "bingham", "lubricant.yield_stress": 300.0,
                     "operating.force": 0.5, "operating.speed": 1.0, "motion.kind": "stop", "motion.duration": 0.01,
                     "motion.mesh_error_bar": False, "solver.max_iterations": 20}
# a Herschel-Bulkley grease stopped on the grease figure's line (+-1 mm, 101 nodes) at 0.5 N
HERSCHEL_BULKLEY_STOP = {"mesh.ny": 1, "mesh.nx": 101, "mesh.x_min": -1e-3, "mesh.x_max": 1e-3,
                         "lubricant.rheology": "herschel_bulkley", "lubricant.yield_stress": 1000.0,
                         "lubricant.flow_index": 0.7, "lubricant.viscosity": 0.5, "operating.force": 0.5,
                         "operating.speed": 1.0, "motion.kind": "stop", "motion.duration": 30.0}
# a smooth elastic line contact on a fixed domain (tests/test_lubricated.py), at Moes' M = 13 and 23
SOFT_FILM = {"effects.asperity_contact": False, "mesh.ny": 1, "mesh.nx": 401, "mesh.x_min": -2.5e-4, "mesh.x_max": 1e-4}
GREASE = {**QUICK, "mesh.nx": 21, "motion.kind": "oscillation", "motion.amplitude": 1e-3, "motion.frequency": 20.0,
          "motion.cycles": 1}
FRETTING = {**GREASE, "motion.amplitude": 50e-6, "motion.frequency": 100.0}  # 50 um at 100 Hz, one cycle

SMOOTH_GREASE = {"effects.asperity_contact": False, "effects.elastic_deformation": False, "mesh.x_min": -1e-3,
                 "mesh.x_max": 1e-3, "lubricant.rheology": "bingham", "lubricant.yield_stress": 1000.0,
                 "operating.force": 0.2, "operating.speed": 1.0}
CASES = {
    # name: (transient?, scene overrides, what happens today, measured)
    "soft_film_M13": (False, {**SOFT_FILM, "operating.speed": 0.003},
                      "the nested solver's film closes at a node; one Newton finishes it (converged)"),
    "soft_film_M23": (False, {**SOFT_FILM, "operating.speed": 0.001},
                      "the nested solver's force balance fails; one Newton finishes it (converged)"),
    # measured in the eighteenth session: not the domain alone. On the Hertz-sized domain
    # [-3.5 b_H, 1.5 b_H] the 51-node line converges (19.9 nm) where 51 x 51 does not, and with
    # the automatic domain 51 x 51 converges at 1 m/s with its thinnest film at the cylinder's
    # ends (306 nm there, 508 nm at the centre), at 0.5 m/s 105 nm there (the line: 279 nm),
    # at 0.3 m/s 20 nm (171 nm), and fails below: where the pressure is ambient at y = +-L/2
    # the end of an uncrowned cylinder sinks less than its middle, and the smooth film closes
    # there first
    "smooth_default_mesh": (False, {"effects.asperity_contact": False, "operating.speed": 0.01},
                            "51 x 51, automatic domain, converged = 0 with h_min = 3.8e-129 m: the smooth film "
                            "closes at the cylinder's ends below ~0.3 m/s (a model without asperity contact "
                            "has no positive film there); 4 s"),
    # the same with the cylinder crowned (geometry.crown_radius, twenty-sixth session): its ends
    # lifted, it failed all the same, at the nested solve's first force balance (the film closed
    # in the automatic domain's cells of 31 um, then sized by sigma) and the Newton from its last
    # state, in 1 s. Since the twenty-seventh session a smooth scene's automatic domain is sized
    # by the Hertz ellipse (cells of 15 um) and a Newton after a closed smooth film starts cold:
    # cold solves converge down to 0.02 m/s (before: 0.5 m/s), and here the Newton stalls at
    # 0.4 of the load in its continuation
    "smooth_crowned_default_mesh": (False, {"effects.asperity_contact": False, "operating.speed": 0.01,
                                            "geometry.crown_radius": 0.1},
                                    "51 x 51, automatic domain, crowned at 0.1 m: converged = 0, the film closed at "
                                    "the first force balance, and one Newton from a cold start stalled at 0.4 of the "
                                    "load in its continuation; 11 s (81 x 51 and 101 x 31 converge)"),
    # found in the eighteenth session: the nested solve starts rigid, and the rigid film the
    # load needs (1 nm) is thinner than cells of 10 um carry, so its first force balance
    # closed the film and `solve` ended in an internal error
    "smooth_coarse_line": (False, {"effects.asperity_contact": False, "operating.speed": 0.01, "mesh.ny": 1,
                                   "mesh.nx": 51, "mesh.x_min": -3.6e-4, "mesh.x_max": 1.55e-4},
                           "converges since one Newton takes a solve whose nested start raised (it ended in an "
                           "internal error), 0.1 s"),
    "grease_1_Pa_s": (True, {**GREASE, "lubricant.viscosity": 1.0},
                      "converges since the squeeze term takes each cell's content (it failed at t = 2.2 ms), "
                      "5.5-8.2 s"),
    # a step's Newton stopped when its deformation residual fell below solver.tolerance times
    # the deformation's range, which these stiff squeeze films never reach: both failed early
    # (2.1e-8 s and 5.3e-9 s). A step's own test (a tenth of its error weight, integrator.Squeeze.settled)
    "grease_10_Pa_s": (True, {**GREASE, "lubricant.viscosity": 10.0},
                       "converges since a step stops at a tenth of its error weight (it failed at t = 2.1e-8 s), "
                       "7 s"),
    # the same oscillation on the default 51-node line (the scene), found in the twentieth
    # session: it failed before that session's changes too (at t = 1.2e-5 s, 20 s), and the
    # memory of the step's non-monotone line search decided it against the 51-node fretting
    # below. Traced in the twenty-first: each failing Newton had met the step's film and force
    # tests and stalled on the steady solve's pressure test (a residual of 1e-6 of the peak
    # pressure, solver.tolerance), a thousandth of the step's own accuracy; where a step's
    # Newton stalls it may now meet the step's own (integrator.Squeeze.settled_pressure), and
    # both run to the end with line-search memories of 1 to 10
    "grease_10_Pa_s_51_nodes": (True, {**GREASE, "mesh.nx": 51, "lubricant.viscosity": 10.0},
                                "converges since a step whose Newton stalls may meet the step's own pressure test "
                                "(it failed at t = 3.1e-6 s), 11-15 s"),
    "fretting_stiff_grease": (True, {**FRETTING, "lubricant.viscosity": 100.0},
                              "converges since a step stops at a tenth of its error weight (it failed at t = 5.3e-9 s), "
                              "24-30 s (a longer alarm, LONGER_BUDGET)"),
    # the same fretting on the default 51-node line (the scene). Traced in the twentieth
    # session: cells sealed at the percolation floor (A_ii ~ 1e-22) whose squeeze outflow swung
    # their scaled residual by 6e9 Pa for a film step of 1e-13 m; then, with that outflow measured
    # as a film change (integrator.Squeeze.outflow_scale_floor), line searches of 1/16 to 1/1024
    # across the inlet's cavitation kinks, and a force balance stalled at 3e-6 of the force
    "fretting_stiff_grease_51_nodes": (True, {**FRETTING, "mesh.nx": 51, "lubricant.viscosity": 100.0},
                                       "converges since a step's sealed cells measure their outflow as a film change, "
                                       "its force balance is judged by the displacement that closes it, and a step whose "
                                       "Newton stalls may meet its own pressure test (a step failed at t = 5.3e-9 s), "
                                       "11-22 s"),
    # found in the twenty-first session, sweeping the 51-node line's oscillations (viscosity
    # 0.1-100 Pa s, 1-20 N): the Table 1 contact with a 1 Pa s oil under fretting failed at
    # t = 6.0e-5 s (6.5 s). Its step's Newton had come within the step's own tests (merit
    # 4.5e-11), then its non-monotone search accepted a 3000-fold rise and it stalled there:
    # a stalled Newton's test is now on its best iterate (monolithic_newton.newton)
    "fretting_1_Pa_s_51_nodes": (True, {**FRETTING, "mesh.nx": 51, "lubricant.viscosity": 1.0},
                                 "converges since a stalled step's Newton is judged on its best iterate (it failed at "
                                 "t = 6.0e-5 s), 4 s"),
    # and under 20 N: the steps crept for minutes (killed at 400 s, t = 15.455 ms) between jumps
    # over impasses at sealing pockets, each jump having reset the creep test's reference to its
    # own length (250 times shorter each time); it keeps the reference since. Then a jump's long
    # step sent both solvers' cylinder away (z = 254 m, 1.6e9 m, ... until numpy overflowed);
    # they refuse a film as large as the cylinder's radius since (evaluation.beyond_the_radius).
    # Then it failed at t = 54.5 ms after 10 jumps, in 25 s: at rest, a 40 MPa pocket trapped
    # beside cells whose pressure the Newton left at -0.8 MPa. Since a rejected step's next
    # attempt follows the error's observed order (integrator.rejection_factor) and a jump starts
    # from the last level, not from the extrapolated one, it runs to the end (twenty-second session)
    "fretting_1_Pa_s_20_N_51_nodes": (True, {**FRETTING, "mesh.nx": 51, "lubricant.viscosity": 1.0,
                                             "operating.force": 20.0},
                                      "converges since a rejected step follows the error's observed order and a jump "
                                      "starts from the last level (it failed at t = 54.5 ms after 10 jumps), 5 jumps, "
                                      "15 s (a longer alarm, LONGER_BUDGET)"),
    "heavy_load_stop": (True, {**QUICK, "operating.force": 20.0, "motion.kind": "stop", "motion.speed": 1.0,
                               "motion.duration": 0.01},
                        "converges since a line contact's step is one Newton (the nested solve failed at 6.0 ms), 3.3-3.5 s"),
    "table1_tight_stop": (True, {**QUICK, "mesh.nx": 31, "operating.speed": 1.0, "motion.kind": "stop",
                                 "motion.tolerance": 1e-5, "motion.duration": 0.01},
                          "converges since a line contact's step is one Newton (the nested solve failed at 7.3 ms), 2.9-3.3 s"),
    # found while changing the force balance (issue 27): with nodal content the same stop failed
    # on 25, 29 and 33 nodes (at 6.6, 8.6, 7.9 ms), and on 31 nodes too once the nested solve's
    # answers moved within its tolerance (the minimum film crept to h = 0, the frozen content's
    # kink, in steps of 1e-16 s). Each cell's content (numerics/control_volume.py) smooths that
    # kink: 25, 29, 31 and 33 nodes all converge (2.3-3.5 s)
    "tight_stop_29_nodes": (True, {**QUICK, "mesh.nx": 29, "operating.speed": 1.0, "motion.kind": "stop",
                                   "motion.tolerance": 1e-5, "motion.duration": 0.01},
                            "converges since the squeeze term takes each cell's content (it failed at t = 8.56 ms "
                            "with dt = 9e-16 s), 2.5-3.5 s"),
    # found in the fifteenth session (issue 27): the tight stop followed to its reconnect.
    # Traced in the sixteenth: an impasse. A pocket node (h/sigma = -0.087) still drained
    # through the percolation floor at 18 MPa against its neighbours' 6.2 MPa, paid by the
    # sliver of its cell above the frozen content's kink; that sliver's film reached the kink
    # as the square root of the time left, and no step's solve converged past it. On 29, 33,
    # 41 and 51 nodes it failed alike (10.0-15.0 ms). In the seventeenth the integrator takes
    # the jump the model makes there (integrator.TimeIntegrator.jump_over_impasse): all five
    # run to the end (tests below)
    "tight_stop_to_reconnect": (True, {**QUICK, "mesh.nx": 31, "operating.speed": 1.0, "motion.kind": "stop",
                                       "motion.tolerance": 1e-5, "motion.duration": 0.02},
                                "converges since the integrator jumps over the impasse at a sealing pocket (a step "
                                "failed at t = 10.67 ms with dt = 4e-12 s), 10-14 s"),
    # listed in docs/DESIGN.md since the twentieth session as too slow to fail cheaply (169 s);
    # measured again in the thirty-ninth: it failed at t = 7.0 ms in 19-23 s, its step Newton
    # finding no descent at a scaled residual of 1.0e-5, after reconnecting at 4.41 ms (the
    # 21-node line ran to its end in 18-19 s, reconnecting at 4.17 ms). Fortieth session: 104 of
    # its 313 solves were failed probes of the step ceiling at rest (integrator.StepCeiling),
    # 14.6 s of its 19.8 s, and the failure came after a probe that passed; with the ceiling's
    # patience it runs to its end (4.41 ms; 4.41 ms on the mesh at rest twice as fine)
    "bingham_stop_automatic_domain": (True, BINGHAM_AUTOMATIC,
                                      "31-node line on the automatic domain: converges since the step ceiling's "
                                      "probes thin out (it failed at t = 7.0 ms, a step's Newton finding no descent), "
                                      "8-9 s"),
    # the same at a tighter motion.tolerance, found with it (fortieth session): it failed at
    # t = 7.7 ms in 11 s, after a step of 0.121 ms had reached a state from which every step,
    # 0.24 ms down to 0.24 us, stalled (at scaled residuals of 4e-6 to 1.4e-5); the run now
    # steps back from such a level of a grease at rest (integrator.TimeIntegrator.run)
    "bingham_stop_automatic_domain_tight": (True, {**BINGHAM_AUTOMATIC, "motion.tolerance": 1e-4},
                                            "the same at motion.tolerance 1e-4: converges since a level at rest from "
                                            "which no step starts is stepped back (it failed at t = 7.7 ms), 20 s"),
    "bingham_stop": (True, {"mesh.ny": 1, "mesh.nx": 101, "mesh.x_min": -1e-3, "mesh.x_max": 1e-3,
                            "lubricant.rheology": "bingham", "lubricant.yield_stress": 100.0,
                            "lubricant.creep_viscosity": 1e8, "operating.force": 2.0,
                            "operating.speed": 1.0, "motion.kind": "stop", "motion.duration": 30.0},
                     "converges since a grease's steps keep the steady Newton's choices (it stalled at t = 1.6 s "
                     "with a Newtonian step's), 5 s"),
    # found this session (issue 28): a sliding contact on its spring under random base vibration.
    # Sliding at 0.1 m/s, or at 5 N, or under a 100 Hz sine, it runs; at rest it runs (12 events)
    "sliding_random_vibration": (True, {**QUICK, "operating.speed": 1.0, "operating.force": 0.5, "motion.kind": "steady",
                                        "motion.duration": 0.005, "motion.mass": 1e-3, "motion.spring_stiffness": 1000.0,
                                        "motion.vibration": "random", "motion.vibration_acceleration": 100.0,
                                        "motion.vibration_frequency": 50.0, "motion.vibration_frequency_end": 500.0},
                                 "converges since no step is shorter than the one whose inertial force the force "
                                 "balance resolves (the first step failed down to t = 1e-12 s: m z'' rounded to more "
                                 "than the force tolerance), 6 s"),
    # found in the twenty-second session (issues 27 and 28) by a scan of tests/test_dynamics.py's
    # light contact (the 31-node stop followed to its reconnect with a mass of 3e-10 to 3e-9 kg,
    # at motion.tolerance 8e-5 to 1.25e-4): this one crept to a seal where every jump failed, its
    # solves started where the predictor extrapolated the mass's ringing (0.1 us) over the jump;
    # a jump starts from the last level since
    "light_mass_stop": (True, {"mesh.ny": 1, "mesh.nx": 31, "operating.speed": 1.0, "motion.kind": "stop",
                               "motion.duration": 0.03, "motion.tolerance": 1.25e-4, "motion.mass": 3e-9},
                        "converges since a jump over an impasse starts from the last level (it failed at a seal "
                        "near t = 10.6 ms), 2 s"),
    # and by the twenty-first session's sweep of the 51-node line's frettings: the 10 Pa s one
    # under 20 N failed at t = 0.36 s (45 s); since a rejected step follows the error's observed
    # order and a jump starts from the last level it runs (7 jumps). From a812f95 to the
    # forty-seventh session it failed again (t = 0.396 s, 14 jumps, 46 s): a jump over an
    # impasse was taken on an answer at the step's usual tests, which no error test checks
    # (unsteady/integrator.line_fallbacks)
    "fretting_10_Pa_s_20_N_51_nodes": (True, {**FRETTING, "mesh.nx": 51, "lubricant.viscosity": 10.0,
                                              "operating.force": 20.0},
                                       "converges since a jump's answer must meet the step's tight tests or be the "
                                       "nested solve's, 7 jumps, 10 s"),
    # the 10 Pa s oscillation on the 51-node line with mass-conserving cavitation, which the
    # transient refused until the thirty-seventh session: each step one Newton on JFO's
    # universal variable (numerics/jfo_outflow.py), its film content carried by the steps
    # and into each predictor (monolithic_newton.warm_iterate). Measured as one run: 7.5 s in
    # the suite (14 s with the mesh error bar's second run), reconnecting within 1 % of the
    # Reynolds condition's run (1.462 against 1.473 s)
    "jfo_oscillation_10_Pa_s_51_nodes": (True, {**GREASE, "mesh.nx": 51, "lubricant.viscosity": 10.0,
                                                "effects.cavitation": "jfo"},
                                         "converges since the transient takes JFO cavitation (it was refused), 7.5 s"),
    # found in the twenty-third session (issues 27 and 28) by a sweep of 2-D scenes: the
    # gallery's grease stop (config/scenes/stop_grease.yaml) under 20 N on its own 51 x 51 mesh.
    # At rest 182 nodes lie at or below the frozen content's kink (h/sigma down to -1.75), 112
    # to 138 cells sealed, their pockets at up to 163 MPa carrying 14.5 of the 20 N; the steps
    # crept to the next seal at t = 0.60 s and every jump (0.014 to 9.4 s) failed in both
    # solvers, the nested one cycling or stalling, the Newton's line search finding no descent
    # (55-63 s). Since a Newtonian film's step projects its trial pressures onto p >= 0
    # (monolithic_newton.projects_pressure, twenty-fourth session), with the exact cell content
    # (numerics/expected_gap_cells.py; with the quadrature's it still fails at t = 0.603 s),
    # the whole 10 s stop runs to its end over 9 jumps (reconnect 3.419 s), but in 224 s of
    # CPU, 685 of its 690 steps before 4 s: the case runs to 0.9 s, past the old failure and
    # its first three jumps (72 s). Since a sealed cell's rate is exact (integrator.bdf_history,
    # twenty-fifth session) it meets the impasse at t = 0.602 s again, where every jump of 4 to
    # 4^6 times the asked step fails and 256 times the failed step converges
    # (integrator.impasse_lengths): 4 jumps, 83 s
    "grease_stop_20_N": (True, {"lubricant.viscosity": 10.0, "operating.force": 20.0, "operating.speed": 1.0,
                                "motion.kind": "stop", "motion.ramp": 1e-3, "motion.duration": 0.9},
                         "converges since a step's line search projects its pressures onto p >= 0, with the exact "
                         "cell content, and a jump tries the failed step's multiples after the long ones (the steps "
                         "crept to a sealing pocket at t = 0.60 s where no jump converged), 4 jumps, 83 s "
                         "(a longer alarm, LONGER_BUDGET)"),
    # found in the twenty-fourth session (issue 27): the one Newton (solver.method newton) on the
    # default 51 x 51 mesh. Its monotone line search halved its steps to 1/32 at two cavitation
    # pairs at the cylinder's ends (h/sigma ~ -0.2, where the outflow's curvature made the full
    # step a thousand times worse) and stalled at a residual of 0.008; its load continuation
    # failed after 26 s. A Newtonian film's steady search is non-monotone since
    "newton_default_mesh": (False, {"solver.method": "newton", "operating.speed": 0.01},
                            "converges since a Newtonian film's steady line search is non-monotone (it stalled, "
                            "and its load continuation failed after 26 s), 10 iterations, 1.2 s"),
    # found in the thirty-eighth session (issue 27): the Table 1 stop on a 2-D mesh with one
    # Newton a step (refused until then). Its GMRES stopped at a tenth of the reduced system's
    # right-hand side, K times a pressure step far larger than the residual: from the sixth
    # step its Newton found no descent, 324 steps were rejected by t = 10 us and the steps
    # crawled at 4 ns. Where a direction does not descend GMRES now solves to the whole residual
    "newton_stop_2d": (True, {"solver.method": "newton", "mesh.nx": 21, "mesh.ny": 21, "operating.speed": 1.0,
                              "motion.kind": "stop", "motion.ramp": 1e-3, "motion.duration": 0.03},
                       "converges since GMRES solves to the whole residual where its first direction does not "
                       "descend (324 steps rejected by t = 10 us), 5 s"),
    # found in the thirty-fourth session (issue 27) at Fig. 8's heaviest force near its lift-off,
    # where the steady contact has more than one state (docs/physics.md section 23): the one
    # Newton's load continuation doubled the load from a lighter converged state and stalled at
    # 0.33 of the force (9 s). In the thirty-fifth session its speed continuation got there
    # (11 s), and then its cold start alone, since the fine mesh starts from its own Reynolds
    # pressure: a fluid share of 0.16 where the nested cold solve finds 0.29 (both are
    # solutions: the nested solve started at the Newton's state stays there)
    "newton_lift_off_20_N": (False, {"solver.method": "newton", "operating.force": 20.0, "operating.speed": 0.0631},
                             "converges from its cold start, 0.3 s"),
    # in the loop (bench/HYSTERESIS.md): the cold start and the load continuation stall, and the
    # speed continuation from half the speed converges (monolithic_newton.continuation_paths) to
    # the contact-carried state, fluid share 0.19 (thirty-fifth session). Since each Newton runs
    # first on the universal variable (monolithic_newton.newton, thirty-seventh session) the load
    # continuation from an eighth of the force converges, to the nested solver's state (fluid
    # load 15.58 N of the 20), in 23-26 s. Since the one Newton's nested start goes down to 13 x 13
    # (forty-second session) its cold start converges, in 1 s, to the contact-carried state (fluid
    # share 0.379, as its cold start finds at 0.0631 m/s), not the nested solver's (0.779): both
    # are states of the loop
    "newton_lift_off_20_N_0100": (False, {"solver.method": "newton", "operating.force": 20.0, "operating.speed": 0.1},
                                  "converges from its cold start, 1 s; by load continuation from an eighth of the force "
                                  "before the forty-second session, 23-26 s"),
    # just above the 51 x 51 loop (bench/HYSTERESIS.md: one state there, fluid share 0.82,
    # which the nested solver reaches): the cold start and every path stalled on the cells' own
    # outflow scales (load at 0.68 of the force, speed at 0.92 of it) until a stalled Newton
    # retried on the open film's scale (monolithic_newton.newton, thirty-sixth session): the
    # load path from a quarter of the force then converges, fluid share 0.8175
    "newton_lift_off_20_N_0158": (False, {"solver.method": "newton", "operating.force": 20.0, "operating.speed": 0.158},
                                  "converges by load continuation from a quarter of the force, 17 s; from its cold "
                                  "start on the universal variable since the thirty-seventh session, 3 s"),
    # Fig. 8's 10 N curve by the one Newton: stalled on the cells' own scales at every start and
    # continuation step (thirty-sixth session); on the open film's scale, by a path, fluid share 0.66.
    # Since each Newton runs on the universal variable first (thirty-seventh session) a start or
    # step that fails runs four Newtons (u and the Fischer-Burmeister function, each retried on
    # the open film's scale): the same state in 22-23 s alone, over 30 s in CI beside other
    # tests (a longer alarm, LONGER_BUDGET)
    "newton_10_N_0063": (False, {"solver.method": "newton", "operating.force": 10.0, "operating.speed": 0.0631},
                         "converges by load continuation from half the force, 10-16 s before the universal "
                         "variable came first, 22-23 s since"),
    # Table 1 by the one Newton at 40 mm/s: stalled on the cells' own scales from the cold start
    # and on both paths (thirty-sixth session)
    "newton_table1_0040": (False, {"solver.method": "newton", "operating.speed": 0.0398},
                           "converges by a continuation path on the open film's outflow scale, 2 s"),
    # Fig. 12's tin connector at 30 N (Table 1's tin, its 31 x 21 mesh): the default solver's
    # nested iteration cycles for 200 iterations and the Newton from its last state stalls; a
    # 2-D nested solve that stops is finished by a cold Newton too since the thirty-sixth
    # session (monolithic_newton.finished_by_newton), here by load continuation
    "fig12_30_N_2d_finish": (False, {"geometry.radius": 0.0025, "operating.force": 30.0, "operating.speed": 2.15,
                                     "mesh.nx": 31, "mesh.ny": 21},
                             "converges by a cold Newton with load continuation after the nested solve stops, "
                             "12.6-13.2 s alone (a longer alarm: beside another case in CI it ran past 30 s)"),
    # the connector grease's scene (config/scenes/connector_grease_bingham.yaml: Table 1, a
    # 300 Pa Bingham grease) slowed on the default 51 x 51 mesh: while each face saw only the
    # gradient across it its Newton stopped unconverged (38 and 35 iterations, 25 and 33 s);
    # with the whole gradient at each face (numerics/yield_stress_reynolds.py, forty-fourth
    # session) 20 and 34 iterations, 1.2 and 1.7 s
    "grease_2d_0_01_m_s": (False, {"lubricant.rheology": "bingham", "lubricant.yield_stress": 300.0,
                                   "operating.speed": 0.01}, "converges with the whole gradient at each face, 1.2 s"),
    "grease_2d_0_003_m_s": (False, {"lubricant.rheology": "bingham", "lubricant.yield_stress": 300.0,
                                    "operating.speed": 0.003}, "converges with the whole gradient at each face, 1.7 s"),
    # the smooth rigid Table 1 cylinder of tests/test_grease_stop.py (a 1 kPa Bingham grease,
    # 0.2 N, 1 m/s, +-1 mm) steady, on finer meshes than that test's 101-node line: found in the
    # forty-fourth session, when its 2-D stop's steady start stalled on 81 x 41: the one Newton
    # from the cold start stalled (at a film of 5 mm on the line, at a scaled residual of 1.34 on
    # 81 x 41) and no cold start of the load continuation converged, in 0.4 and 2 s; since the
    # forty-fifth session the yield stress's continuation reaches both
    # (monolithic_newton.continuation_paths)
    "grease_smooth_line_151_nodes": (False, {**SMOOTH_GREASE, "mesh.nx": 151, "mesh.ny": 1},
                                     "converges by yield-stress continuation from 1/2 of the yield stress, 1.2 s "
                                     "(10.324 um; a shooting solver 10.329 um)"),
    "grease_smooth_2d_stiff_creep": (False, {**SMOOTH_GREASE, "mesh.nx": 81, "mesh.ny": 41,
                                             "lubricant.creep_viscosity": 1e8},
                                     "converges by yield-stress continuation from 1/2 of the yield stress, 1.0 s "
                                     "(6.667 um, as at the default creep viscosity of 1e4 Pa s)"),
    # a strongly shear-thinning Herschel-Bulkley film on the smooth rigid Table 1 line at 1 m/s
    # (docs/physics.md section 21, open since the thirty-ninth session); added to the suite in
    # the forty-fifth, when the yield stress's continuation did not reach it either
    "herschel_bulkley_n_0_7": (False, {"effects.asperity_contact": False, "effects.elastic_deformation": False,
                                       "mesh.ny": 1, "mesh.nx": 101, "operating.speed": 1.0,
                                       "lubricant.rheology": "herschel_bulkley", "lubricant.yield_stress": 300.0,
                                       "lubricant.flow_index": 0.7, "lubricant.viscosity": 0.5},
                               "converges since the forty-sixth session from the Newtonian stand-in at the grease's "
                               "flowing viscosity (model/grease_start.py), to 6.7 nm where the shooting solver gives "
                               "18.8 nm: its 35 um pressure zone spans 2.5 of the automatic domain's 16 um cells, and the "
                               "notes say so (validity.resolution_note); before, the Newton from the consistency's "
                               "2.45 um film ran to a film of 9 mm, 1-2 s"),
    # a Herschel-Bulkley grease stopped on the grease figure's line (forty-sixth session): at rest
    # its step Newton stalled near its answer under the steady tests (a plug's rows at the yield
    # limit), and the run crept on at steps of 1e-9 s to the 20 000-step limit in 146 s
    "herschel_bulkley_stop": (True, HERSCHEL_BULKLEY_STOP,
                              "converges since a grease's step that failed once from a level is retried with a "
                              "Newtonian step's tests (integrator.grease_step_retry); it crept at 1e-9 s steps, 146 s"),
    # the same with a creep viscosity of 1e8 Pa s (the grease figure's): failed at the end of the
    # deceleration (t = 1.0 ms, 6-15 s). Traced in the forty-seventh session: each step's first
    # attempt stalled under the steady tests, its retry at a quarter of the step passed with a
    # Newtonian step's, the next step three times longer failed again, and the steps shrank
    # towards the breakpoint until one was too short to be needed
    "herschel_bulkley_stop_creep_1e8": (True, {**HERSCHEL_BULKLEY_STOP, "lubricant.creep_viscosity": 1e8},
                                        "converges since a grease's steps that stall under the steady tests at steps "
                                        "shorter than accuracy needs switch to a Newtonian step's tests "
                                        "(integrator.TimeIntegrator.step_tests_from), 90-92 levels, 12-30 s (a longer "
                                        "alarm, LONGER_BUDGET)"),
}


@dataclass
class Outcome:
    result: object  # the Dataset, or the exception the run raised
    seconds: float


class OverBudget(Exception):
    pass


# The budgets above are wall clock on the machine of bench/SOLVER_CORE.md at 0e5477e (2026-12-01), where
# one SuperLU factorisation of the five-point Laplacian on 201 x 201 nodes (that file's unit)
# took this many CPU seconds; on a slower machine each budget grows in proportion, never
# shrinks. The forty-sixth session's machine took 0.28-0.31 s, and its cases about twice as long
# (newton_10_N_0063 89 s alone against 22-23 s, the automatic-domain Bingham stop 26 s against
# 8-9 s), which had failed nine budget tests that are alarms against a hang, not speed tests.
REFERENCE_FACTORISATION = 0.146


@functools.cache
def machine_slowness() -> float:
    """This machine's factorisation time over REFERENCE_FACTORISATION, at least 1 (median of 5, CPU s):
    the unit bench/solver_core.factorisation_unit times, which tests cannot import (bench is no package)."""
    second = sp.diags([-1.0, 2.0, -1.0], [-1, 0, 1], shape=(201, 201))
    laplacian = sp.csc_matrix(sp.kronsum(second, second))
    times = []
    for _ in range(5):
        start = time.process_time()
        splu(laplacian)
        times.append(time.process_time() - start)
    return max(1.0, statistics.median(times) / REFERENCE_FACTORISATION)


def budget(case):
    return math.ceil(LONGER_BUDGET.get(case, BUDGET) * machine_slowness())


# A transient case is one run: the mesh error bar a run makes by default (motion.mesh_error_bar)
# is the same case again on a finer mesh at rest, whose failure leaves the extrapolation NaN and
# says so (tests/test_error_bar.py); here it would multiply each case's cost several times
ONE_RUN = {"motion.mesh_error_bar": False}


def run_within_budget(case):
    transient, overrides, _ = CASES[case]
    scene = lc.load_scene(TABLE1, {**ONE_RUN, **overrides} if transient else overrides)

    def over(signum, frame):
        raise OverBudget(f"{case} ran longer than {budget(case)} s")

    previous = signal.signal(signal.SIGALRM, over)
    signal.alarm(budget(case))
    start = time.perf_counter()
    try:
        result = lc.transient(scene, progress=False) if transient else lc.solve(scene)
    except (ValueError, lc.SceneError) as error:
        result = error
    finally:
        signal.alarm(0)
        signal.signal(signal.SIGALRM, previous)
    return Outcome(result, time.perf_counter() - start)


@pytest.fixture(scope="module")
def outcomes():
    cache = {}

    def outcome(case):
        if case not in cache:
            cache[case] = run_within_budget(case)
        return cache[case]

    return outcome


# converged at default settings since a nested solve that stops is finished by one Newton
# (model/monolithic_newton.finished_by_newton, docs/physics.md section 20), and a line
# contact's time step is one Newton (unsteady/integrator.step_solve)
CONVERGED = {"soft_film_M13", "soft_film_M23", "smooth_coarse_line", "heavy_load_stop", "table1_tight_stop", "grease_1_Pa_s",
             "tight_stop_29_nodes", "tight_stop_to_reconnect", "grease_10_Pa_s", "grease_10_Pa_s_51_nodes", "fretting_stiff_grease",
             "fretting_stiff_grease_51_nodes", "fretting_1_Pa_s_51_nodes", "fretting_1_Pa_s_20_N_51_nodes",
             "fretting_10_Pa_s_20_N_51_nodes",
             "sliding_random_vibration", "bingham_stop", "light_mass_stop",
             "grease_stop_20_N", "newton_default_mesh", "newton_lift_off_20_N", "newton_lift_off_20_N_0100",
             "newton_lift_off_20_N_0158", "newton_10_N_0063", "newton_table1_0040", "fig12_30_N_2d_finish",
             "jfo_oscillation_10_Pa_s_51_nodes", "newton_stop_2d",
             "bingham_stop_automatic_domain", "bingham_stop_automatic_domain_tight", "grease_2d_0_01_m_s",
             "grease_2d_0_003_m_s", "grease_smooth_line_151_nodes", "grease_smooth_2d_stiff_creep", "herschel_bulkley_n_0_7",
             "herschel_bulkley_stop", "herschel_bulkley_stop_creep_1e8"}


def failing_today(case):
    if case in CONVERGED:
        return case
    return pytest.param(case, marks=pytest.mark.xfail(strict=True, reason=f"issue 27: {CASES[case][2]}"))


@pytest.mark.parametrize("case", [failing_today(case) for case in CASES])
def test_hard_case_converges_and_says_so(case, outcomes):
    ds = outcomes(case).result
    assert not isinstance(ds, Exception), ds
    assert ds["converged"].item() == 1 and "NOT CONVERGED" not in ds.attrs["notes"]
    if CASES[case][1].get("effects.asperity_contact") is False:  # a smooth contact stands on a film (Moes: 6-21 nm)
        assert ds["min_film_thickness"].item() > 1e-9
    if case == "newton_10_N_0063":  # reached by a path: the note says which, since the path decides the state
        assert "one Newton reached this point by load continuation from 0.5 of the force" in ds.attrs["notes"]
    if case == "herschel_bulkley_n_0_7":  # converged on a mesh too coarse for its film, and says so
        assert "the fluid pressure's width" in ds.attrs["notes"] and "mesh.nx of at least" in ds.attrs["notes"]
    if case == "herschel_bulkley_stop_creep_1e8":  # its steps switched tests, and it says from when
        assert re.search(r"from t = \S+ s the grease's steps stalled under the steady tests", ds.attrs["notes"])
    if case == "fretting_1_Pa_s_20_N_51_nodes":  # a jump while it still moved: its length bounds nothing, and it says so
        jumped = ds["impasse_jump"].values.astype(bool)
        starts = ds["time"].values[np.flatnonzero(jumped) - 1]  # a jump's step starts at the level before it
        moving = starts < CASES[case][1]["motion.cycles"] / CASES[case][1]["motion.frequency"]
        assert ("while the contact still moved" in ds.attrs["notes"]) == bool(moving.any()), ds.attrs["notes"]
    if case == "fig12_30_N_2d_finish":  # the default solver says which solver converged it, and how
        assert "the nested solver stopped" in ds.attrs["notes"] and "one Newton from a cold start" in ds.attrs["notes"]


STEP_FAILURE = re.compile(r"NOT CONVERGED: time step at t = (\S+) s \(dt = (\S+) s\) (?:did not converge|was not taken) "
                          r"\(\d+ attempt\(s\) in a row(?:; below motion.tolerance [^)]*)?(?:; \S+ s is the shortest step [^)]*)?\): (.+)")


@pytest.mark.parametrize("case", list(CASES))
def test_hard_case_fails_cheaply_saying_where_and_why(case, outcomes):
    outcome = outcomes(case)
    assert outcome.seconds < budget(case)
    ds = outcome.result
    if isinstance(ds, Exception):  # refused: the message says why, with the number
        assert "positive film everywhere" in str(ds) and "min h =" in str(ds)
        return
    if ds["converged"].item() == 1:
        return
    notes = ds.attrs["notes"]
    if not CASES[case][0]:  # a steady case: the force balance says how far it got
        assert re.search(r"NOT CONVERGED: (force balance did not converge \(z = \S+ m, force error \S+ N"
                         r"|[^;]+; load continuation(?: stopped at \S+ of the force|: no cold start converged))", notes), \
            notes  # the nested solver, or the one Newton and how far its continuation got
        if "speed continuation" in notes:  # the one Newton says how far each path got
            assert re.search(r"; speed continuation(?: stopped at \S+ of the speed: |: no cold start converged)", notes), notes
        if "yield-stress continuation" in notes:
            assert re.search(r"; yield-stress continuation(?: stopped at \S+ of the yield stress: |: no cold start "
                             r"converged)", notes), notes
        if case == "smooth_default_mesh":  # and what an engineer can do about it
            assert "thinnest at its ends" in notes and "effects.asperity_contact" in notes, notes
        if case == "smooth_crowned_default_mesh":  # not the ends, which the crown lifts
            assert "thinnest at its ends" not in notes and "is crowned" in notes and "(mesh.nx)" in notes, notes
        assert np.isfinite(ds["central_film_thickness"].item())
        return
    where = STEP_FAILURE.search(notes)
    assert where, notes
    failed_at, step = float(where.group(1)), float(where.group(2))
    times = ds["time"].values
    # the series up to the last accepted step is kept (the start at least), and the failed step
    # comes right after it (the message gives dt to three digits)
    assert times.size >= 1 and times[0] == 0.0 and times[-1] == pytest.approx(failed_at - step, rel=1e-5, abs=1e-3 * step)
    for name in ("min_film_thickness", "fluid_force", "contact_force"):
        assert np.all(np.isfinite(ds[name].values)), name
    assert not np.any(np.isnan(ds["contact_resistance"].values))
    if "creep towards a sealing pocket" in where.group(3):  # the steps crept to a seal: where, and that jumps failed
        assert re.search(r"a pocket of the film is sealing at x = \S+ mm, y = \S+ mm \(h/sigma = ", notes), notes
        assert ("but no longer step (up to 4096 times) converged either, nor a shorter one of 4, 16, ... times the "
                "failed step") in notes, notes
        return
    # both solvers named, or the one Newton named as the only solver (mass, spring, grease)
    assert "one Newton" in where.group(3)
    assert "nested coupled solve" in where.group(3) or "the only solver" in where.group(3)


def test_a_jump_over_an_impasse_is_said_and_lands_where_looser_tolerances_point(outcomes):
    """The tight stop meets the impasse of a sealing pocket at 10.6 ms (docs/physics.md section
    14) and jumps over it, saying where, how often and over how long a step. Independent truth:
    the same stop at 1e-3 and 2e-4, extrapolated in the tolerance (BDF2's global error goes as
    tol^(2/3), unsteady/transient.ERROR_ORDER_IN_TOLERANCE), puts the reconnect time at 1e-5
    within 1 % of where the jumping run lands (measured: 13.655 against 13.641 ms). The looser
    runs' steps may meet an impasse too (2e-4 jumps once, over 21 us, since a rejected step
    follows the error's observed order): a time within a jump is uncertain by its length, which
    the extrapolation carries into the prediction ((1 + k) times the 2e-4 run's, k times the
    1e-3 run's, k = 0.45 its factor); that must stay below a quarter of the 1 % compared
    (measured: 0.22 %), or the comparison would test the jumps, not the time integration."""
    ds = outcomes("tight_stop_to_reconnect").result
    notes = ds.attrs["notes"]
    jumps = ds["impasse_jumps"].item()
    assert jumps >= 1 and f"{jumps} impasse jump(s)" in notes and ds["impasse_jump"].sum() == jumps
    assert "a pocket sealing at x = 0 mm" in notes and "accepted without the error test" in notes
    assert 0.0 < ds["longest_impasse_jump"].item() < 1e-3 * ds["reconnect_time"].item()
    # the jumps before the reconnection, by hand from the series' own flags
    times, flags = ds["time"].values, ds["impasse_jump"].values
    motion = lc.load_scene(TABLE1, CASES["tight_stop_to_reconnect"][1]).motion
    stopped = motion.stop_time + motion.ramp  # the rest begins: reconnect_time counts from there
    by_hand = sum(times[k] - times[k - 1] for k in np.flatnonzero(flags)
                  if times[k - 1] < stopped + ds["reconnect_time"].item())
    assert ds["reconnect_time_jumps"].item() == pytest.approx(by_hand, rel=1e-12) and by_hand > 0.0
    assert f"reconnect_time_jumps = {by_hand:.3g} s (impasse jumps before the reconnection" in summary(ds)
    _, overrides, _ = CASES["tight_stop_to_reconnect"]
    looser, jump = {}, {}
    for tolerance in (1e-3, 2e-4):
        run = lc.transient(lc.load_scene(TABLE1, {**overrides, "motion.tolerance": tolerance}), progress=False)
        assert run["converged"].item() == 1
        looser[tolerance], jump[tolerance] = run["reconnect_time"].item(), run["longest_impasse_jump"].item()
    weight = {tolerance: tolerance ** (2.0 / 3.0) for tolerance in (1e-3, 2e-4, 1e-5)}
    k = (weight[2e-4] - weight[1e-5]) / (weight[1e-3] - weight[2e-4])
    predicted = looser[2e-4] + (looser[2e-4] - looser[1e-3]) * k
    assert (1.0 + k) * jump[2e-4] + k * jump[1e-3] < 0.25 * 0.01 * predicted
    assert ds["reconnect_time"].item() == pytest.approx(predicted, rel=0.01)


def test_where_no_jump_converges_the_failure_names_the_sealing_pocket(monkeypatch):
    """Without the jump (no probe allowed) the tight stop ends at the impasse, where its steps
    creep towards the kink (integrator.CREEPING), and says so, where the pocket drains and that
    a looser motion.tolerance may step over it."""
    monkeypatch.setattr(integrator, "IMPASSE_PROBES", 0)
    _, overrides, _ = CASES["tight_stop_to_reconnect"]
    ds = lc.transient(lc.load_scene(TABLE1, overrides), progress=False)
    notes = ds.attrs["notes"]
    assert ds["converged"].item() == 0 and ds["impasse_jumps"].item() == 0
    assert STEP_FAILURE.search(notes), notes
    assert "a pocket of the film is sealing at x = 0 mm" in notes and "a looser motion.tolerance" in notes
    assert "was not taken" in notes and integrator.CREEPING in notes and "since the motion last changed" in notes
