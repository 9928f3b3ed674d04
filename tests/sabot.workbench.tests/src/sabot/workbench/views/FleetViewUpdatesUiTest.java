package sabot.workbench.views;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertFalse;
import static org.junit.jupiter.api.Assertions.assertNotNull;
import static org.junit.jupiter.api.Assertions.assertTrue;

import java.time.Instant;
import java.util.Comparator;
import java.util.List;
import java.util.Locale;
import java.util.function.BooleanSupplier;
import java.util.function.Supplier;
import java.util.stream.IntStream;

import org.eclipse.swt.widgets.Display;
import org.eclipse.swt.widgets.TableItem;
import org.eclipse.ui.PlatformUI;
import org.junit.jupiter.api.AfterEach;
import org.junit.jupiter.api.Test;

import sabot.controlml.payload.MissionState;
import sabot.controlml.payload.MissionStatus;
import sabot.workbench.fleet.Availability;
import sabot.workbench.fleet.RobotState;

/**
 * The Fleet view under a hundred robots' telemetry, driven burst by burst through a {@link DrivenFleet} in the real
 * workbench: the rows follow at most every {@link FleetView#UPDATE_MS} ms, and only the changed ones, while sorting,
 * filtering, presence, arrivals and departures stay right.
 */
class FleetViewUpdatesUiTest {

    static final int ROBOTS = 100;
    static final int BURSTS = 40;

    private DrivenFleet fleet;
    private FleetView view;

    @AfterEach
    void closeFleet() {
        if (view != null) {
            view.setFilter("");
            view.sortBy(0);
            if (view.table().getSortDirection() != org.eclipse.swt.SWT.UP) {
                view.sortBy(0);
            }
        }
        if (fleet != null) {
            fleet.close();
            waitFor(() -> drivenRows().isEmpty(), 10, () -> "driven robots still shown: " + drivenRows().size());
        }
    }

    @Test
    void burstsOfTelemetryRewriteTheRowsAtMostEveryUpdatePeriodAndShowTheLatest() {
        view = fleetView();
        start();
        assertEquals(ROBOTS, drivenRows().size(), "robots that came are shown at once");

        long written0 = view.rowsWritten();
        long t0 = System.nanoTime();
        for (int b = 1; b <= BURSTS; b++) {
            Instant at = Instant.now();
            for (int i = 0; i < ROBOTS; i++) {
                RobotState r = fleet.get(DrivenFleet.jid(i));
                fleet.put(r.withPose(DrivenFleet.pose(x(i) + 0.01 * b, y(i), 0.02 * b, at), at, DrivenFleet.receipt(at)));
            }
            drain();
        }
        // the last burst reaches the rows by the timer, at most one period later
        waitFor(this::rowsShowTheFleet, 10, () -> "rows not brought to the latest poses");
        long elapsedMs = (System.nanoTime() - t0) / 1_000_000;
        long written = view.rowsWritten() - written0;
        // one update when the first burst came (the last was longer ago than the period), then one a period at most
        long bound = ROBOTS * (elapsedMs / FleetView.UPDATE_MS + 2);
        System.out.printf(Locale.ROOT, "[figure] Fleet view: %d bursts of %d robots in %d ms: %d rows written (%.1f "
                + "a burst; without coalescing %d)%n", BURSTS, ROBOTS, elapsedMs, written, written / (double) BURSTS,
                BURSTS * ROBOTS);
        assertTrue(written >= ROBOTS, "the latest poses were written: " + written);
        assertTrue(written <= bound, written + " rows written for " + BURSTS + " bursts in " + elapsedMs + " ms: more "
                + "than " + ROBOTS + " rows every " + FleetView.UPDATE_MS + " ms (bound " + bound + ")");
    }

    @Test
    void sortFilterPresenceArrivalAndDepartureStayRightUnderBursts() {
        view = fleetView();
        start();
        // sorted by pose x: bursts turn the robots' order round
        view.sortBy(2);
        Instant at = Instant.now();
        for (int i = 0; i < ROBOTS; i++) {
            RobotState r = fleet.get(DrivenFleet.jid(i));
            fleet.put(r.withPose(DrivenFleet.pose(10 - 0.09 * i, 4, 0, at), at, DrivenFleet.receipt(at)));
            drain();
        }
        waitFor(() -> drivenRows().equals(expected(Comparator.comparingDouble(r -> r.pose().pose().x()))), 10,
                () -> "rows not sorted by x: " + names(drivenRows()));

        // a presence change is shown at once, before the period is up
        RobotState five = fleet.get(DrivenFleet.jid(5)).withPresence(Availability.AWAY, "charging");
        fleet.put(five);
        drain();
        assertEquals("Away — charging", item(five.jid()).getText(1));

        // the filter on a mission's detail: the rows that come to match it appear
        view.setFilter("docking");
        assertTrue(drivenRows().isEmpty(), names(drivenRows()).toString());
        at = Instant.now();
        for (int i = 0; i < 10; i++) {
            RobotState r = fleet.get(DrivenFleet.jid(i));
            fleet.put(r.withMission(new MissionStatus(MissionState.RUNNING, false, 50, "docking"), at));
        }
        drain();
        waitFor(() -> names(drivenRows()).equals(IntStream.range(0, 10).mapToObj(i -> String.format("driven-%03d", 9
                - i)).toList()), 10, () -> "rows of the filter 'docking': " + names(drivenRows()));
        view.setFilter("");

        // a robot that leaves, and one that comes, at once
        fleet.remove(DrivenFleet.jid(3));
        drain();
        assertFalse(names(drivenRows()).contains("driven-003"), "a removed robot is still shown");
        fleet.put(DrivenFleet.busy(ROBOTS, 0.5, 0.5, 0, Instant.now()));
        drain();
        assertTrue(names(drivenRows()).contains(String.format("driven-%03d", ROBOTS)), "a new robot is not shown");
        assertEquals(ROBOTS, drivenRows().size());
    }

    private void start() {
        fleet = new DrivenFleet();
        Instant at = Instant.now();
        for (int i = 0; i < ROBOTS; i++) {
            fleet.put(DrivenFleet.busy(i, x(i), y(i), 0, at));
        }
        drain();
    }

    /** Robot i's start: a 10 x 10 grid over the 12 x 9 m room. */
    static double x(int i) {
        return 1 + (i % 10) * 1.0;
    }

    static double y(int i) {
        return 0.8 + (i / 10) * 0.75;
    }

    private boolean rowsShowTheFleet() {
        Instant now = Instant.now();
        for (TableItem item : view.table().getItems()) {
            if (item.getData() instanceof RobotState shown && shown.jid().endsWith("@" + DrivenFleet.DOMAIN)) {
                RobotState latest = fleet.get(shown.jid());
                if (shown != latest || !item.getText(2).equals(FleetView.texts(latest, now).get(2))) {
                    return false;
                }
            }
        }
        return true;
    }

    private List<RobotState> expected(Comparator<RobotState> order) {
        return fleet.robots().stream().sorted(order).toList();
    }

    private List<RobotState> drivenRows() {
        return fleetView().rows().stream().filter(r -> r.jid().endsWith("@" + DrivenFleet.DOMAIN)).toList();
    }

    private static List<String> names(List<RobotState> rows) {
        return rows.stream().map(RobotState::name).toList();
    }

    private TableItem item(String jid) {
        for (TableItem item : view.table().getItems()) {
            if (item.getData() instanceof RobotState r && r.jid().equals(jid)) {
                return item;
            }
        }
        throw new AssertionError("no row for " + jid);
    }

    static FleetView fleetView() {
        FleetView v = (FleetView) PlatformUI.getWorkbench().getActiveWorkbenchWindow().getActivePage().findView(
                FleetView.ID);
        assertNotNull(v, "fleet view not open");
        return v;
    }

    /** Runs what is queued on the UI thread now (timers that are not due yet stay queued). */
    static void drain() {
        Display d = Display.getCurrent();
        while (d.readAndDispatch()) {
            // the fleet bindings' refreshes, paints
        }
    }

    static void waitFor(BooleanSupplier condition, double seconds, Supplier<String> what) {
        Display d = Display.getCurrent();
        long deadline = System.nanoTime() + (long) (seconds * 1e9);
        while (!condition.getAsBoolean()) {
            if (System.nanoTime() > deadline) {
                throw new AssertionError("within " + seconds + " s: " + what.get());
            }
            d.timerExec(20, () -> {
            });
            if (!d.readAndDispatch()) {
                d.sleep();
            }
        }
    }
}
