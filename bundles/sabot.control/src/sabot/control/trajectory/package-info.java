/**
 * Geometry separated from timing: planner waypoints become an {@link sabot.control.trajectory.ArcLengthSpline}
 * (a C&sup2; cubic spline re-parameterised by arc length, with first and second derivatives), a
 * {@link sabot.control.trajectory.TimeLaw} s(t) respects v_max, a_max and the lateral-acceleration limit, and
 * {@link sabot.control.trajectory.SplineTrajectory} rebuilds the commands v(t) = v'(s)&middot;s&#775;(t),
 * &omega;(t) = &omega;'(s)&middot;s&#775;(t) = &kappa;(s)&middot;s&#775;(t). Turns in place and sequences with stops complete
 * the set.
 */
package sabot.control.trajectory;
