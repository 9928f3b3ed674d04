package sabot.controlml.payload;

/**
 * The upper triangle of a planar pose's 3x3 covariance (x, y, theta).
 *
 * @param xx         var(x) in m&sup2;
 * @param xy         cov(x, y) in m&sup2;
 * @param xTheta     cov(x, theta) in m&middot;rad
 * @param yy         var(y) in m&sup2;
 * @param yTheta     cov(y, theta) in m&middot;rad
 * @param thetaTheta var(theta) in rad&sup2;
 */
public record PoseCovariance(double xx, double xy, double xTheta, double yy, double yTheta, double thetaTheta) {

    /** No uncertainty. */
    public static final PoseCovariance ZERO = new PoseCovariance(0, 0, 0, 0, 0, 0);

    /** @return a diagonal covariance */
    public static PoseCovariance diagonal(double xx, double yy, double thetaTheta) {
        return new PoseCovariance(xx, 0, 0, yy, 0, thetaTheta);
    }
}
