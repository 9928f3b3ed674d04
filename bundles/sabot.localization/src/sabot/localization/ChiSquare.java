package sabot.localization;

/** Chi-square quantiles for the Mahalanobis gate, for 1 to 3 degrees of freedom. */
final class ChiSquare {

    private ChiSquare() {
    }

    /** @return q such that P(&chi;&sup2;_k &le; q) = p, by bisection on the closed-form CDFs */
    static double quantile(int k, double p) {
        double lo = 0;
        double hi = 200;
        for (int i = 0; i < 200; i++) {
            double mid = (lo + hi) / 2;
            if (cdf(k, mid) < p) {
                lo = mid;
            } else {
                hi = mid;
            }
        }
        return (lo + hi) / 2;
    }

    static double cdf(int k, double q) {
        return switch (k) {
            case 1 -> erf(Math.sqrt(q / 2));
            case 2 -> 1 - Math.exp(-q / 2);
            case 3 -> erf(Math.sqrt(q / 2)) - Math.sqrt(2 * q / Math.PI) * Math.exp(-q / 2);
            default -> throw new IllegalArgumentException("degrees of freedom 1..3 supported, got " + k);
        };
    }

    /** Abramowitz and Stegun 7.1.26 is too coarse at the tails; use a series/continued fraction via erfc. */
    static double erf(double z) {
        // erf by its Taylor series for small z, complementary continued fraction (Lentz) otherwise.
        if (z < 2.5) {
            double sum = z;
            double term = z;
            for (int n = 1; n < 200; n++) {
                term *= -z * z / n;
                double add = term / (2 * n + 1);
                sum += add;
                if (Math.abs(add) < 1e-17) {
                    break;
                }
            }
            return 2 / Math.sqrt(Math.PI) * sum;
        }
        // erfc(z) = exp(-z^2)/sqrt(pi) * 1/(z + 1/2/(z + 1/(z + 3/2/(z + ...))))
        double f = z;
        for (int n = 60; n >= 1; n--) {
            f = z + (n / 2.0) / f;
        }
        return 1 - Math.exp(-z * z) / Math.sqrt(Math.PI) / f;
    }
}
