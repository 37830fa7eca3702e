"""How a run of the compiled integrator ends, and when it checks its pace: constants the
kernel compiles in and the Python side reads without loading the compiler."""

# what a run ends with (its status); the info row says where: t, then details
RUN_FINISHED = 0
RUN_SINGULAR = 1        # stopped within singular_stop of a singular configuration (an event)
FAIL_ASSEMBLY = 2       # the loops cannot close at a stage
FAIL_SINGULAR = 3       # a stage lands on a singular configuration
FAIL_LAW = 4            # a law is not finite (info[1]: which)
FAIL_MASS = 5           # the mass matrix is singular
FAIL_SPRING = 6         # a spring's or damper's ends meet
FAIL_STEP = 7           # the step fell below the resolution of t
FAIL_DIVERGED = 8       # q or q' is no longer finite
FAIL_BUDGET = 9         # the run took its budget of evaluations before reaching t1
FAIL_PACE = 10          # at PACE_CHECK evaluations the run had gone too short a way to reach t1
                        # within PACE_MARGIN times its budget at that pace
PACE_CHECK = 2000       # evaluations after which a run's pace is checked against its budget:
PACE_MARGIN = 10        # it stops when that pace would take this many times its budget (a run
                        # starts slower than it goes on, while its first steps find their size)
