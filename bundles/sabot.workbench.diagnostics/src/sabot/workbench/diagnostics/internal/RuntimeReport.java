package sabot.workbench.diagnostics.internal;

import java.util.ArrayList;
import java.util.Comparator;
import java.util.List;

import org.osgi.framework.Bundle;
import org.osgi.framework.BundleContext;

/** What the diagnostics view shows: the Java runtime and every installed bundle with its state. */
final class RuntimeReport {

    /**
     * One installed bundle.
     *
     * @param id           the framework's bundle id
     * @param symbolicName the bundle symbolic name
     * @param version      the bundle version
     * @param state        INSTALLED, RESOLVED, STARTING, STOPPING, ACTIVE or UNINSTALLED
     */
    record BundleRow(long id, String symbolicName, String version, String state) {
    }

    private RuntimeReport() {
    }

    static List<BundleRow> bundles(BundleContext context) {
        List<BundleRow> rows = new ArrayList<>();
        for (Bundle b : context.getBundles()) {
            rows.add(new BundleRow(b.getBundleId(), b.getSymbolicName(), b.getVersion().toString(), state(b
                    .getState())));
        }
        rows.sort(Comparator.comparing(BundleRow::symbolicName, Comparator.nullsFirst(Comparator.naturalOrder())));
        return rows;
    }

    static String state(int state) {
        return switch (state) {
            case Bundle.INSTALLED -> "INSTALLED";
            case Bundle.RESOLVED -> "RESOLVED";
            case Bundle.STARTING -> "STARTING";
            case Bundle.STOPPING -> "STOPPING";
            case Bundle.ACTIVE -> "ACTIVE";
            case Bundle.UNINSTALLED -> "UNINSTALLED";
            default -> "UNKNOWN(" + state + ")";
        };
    }

    static String summary(BundleContext context) {
        long active = context.getBundles().length == 0 ? 0 : java.util.Arrays.stream(context.getBundles())
                .filter(b -> b.getState() == Bundle.ACTIVE).count();
        return String.format("Java %s (%s), %d bundles, %d active, max heap %d MiB", Runtime.version(),
                System.getProperty("java.vendor"), context.getBundles().length, active,
                Runtime.getRuntime().maxMemory() / (1024 * 1024));
    }
}
