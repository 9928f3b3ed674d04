/**
 * Time-parameterised references a tracking controller follows: {@link sabot.model.path.Trajectory} and its
 * {@link sabot.model.path.TrajectorySample}. Map frame, SI units and radians; time in seconds from the trajectory's
 * start.
 */
package sabot.model.path;
