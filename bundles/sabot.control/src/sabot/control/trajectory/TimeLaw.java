package sabot.control.trajectory;

import org.osgi.annotation.versioning.ProviderType;

/** A time law s(t) along a path of known length: how far along it the reference is at each instant. */
@ProviderType
public interface TimeLaw {

    /** @return seconds from start to end, &ge; 0 */
    double duration();

    /** @return the path length it covers, metres */
    double distance();

    /**
     * @param t   seconds, clamped to [0, duration]
     * @param out receives {s (m), s&#775; (m/s), s&#776; (m/s&sup2;)}
     */
    void evaluate(double t, double[] out);
}
