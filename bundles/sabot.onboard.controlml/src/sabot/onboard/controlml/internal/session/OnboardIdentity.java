package sabot.onboard.controlml.internal.session;

import java.util.ArrayList;
import java.util.Comparator;
import java.util.List;
import java.util.Map;

import sabot.identity.DeviceProfile;
import sabot.identity.DeviceUrn;
import sabot.identity.HardwareDescription;
import sabot.identity.Inventory;
import sabot.identity.InventorySource;

/**
 * The robot's vCard identity (docs/IDENTITY.md): profile and QR inventory of the running onboard product. The
 * inventory lists the framework's bundles (from {@link InventorySource}) and, among the applications, each running
 * task as {@code sabot.task.<name>} with the version of the bundle that provides it.
 * <p>
 * Until the robot description carries a serial number, the serial is the robot's bare JID: unique in a fleet and
 * stable, so the vCard's {@code urn:uuid:} stays the same across restarts.
 */
final class OnboardIdentity {

    static final String CATEGORY = "mobile robot (differential drive)";
    static final String MANUFACTURER = "Sabot";
    static final String MODEL = "Sabot Onboard";
    static final String ROLE = "robot";
    static final String BOARD = "onboard computer";

    private OnboardIdentity() {
    }

    /** @return the serial the URN is derived from */
    static String serial(ControlMlSettings settings) {
        return settings.jid().toString();
    }

    /**
     * @param version the onboard product's version (the sabot.onboard bundle's)
     * @param tasks   running task name to the version of its bundle
     * @param page    the robot's web page (the vCard's URL), or null when no task serves one
     */
    static DeviceProfile profile(ControlMlSettings settings, String version, Map<String, String> tasks,
            java.net.URI page) {
        String description = MODEL + " " + version + "; tasks: " + (tasks.isEmpty() ? "none" : String.join(", ",
                tasks.keySet()));
        return new DeviceProfile(CATEGORY, MANUFACTURER, MODEL, settings.robotName(), page, null, null, DeviceUrn
                .urnOf(serial(settings)), settings.jid().toString(), ROLE, null, null, description);
    }

    /** @param tasks running task name to the version of its bundle */
    static Inventory inventory(InventorySource source, ControlMlSettings settings, Map<String, String> tasks) {
        Inventory base = source.inventory(new HardwareDescription(serial(settings), new Inventory.Mechanic(MODEL,
                List.of()), BOARD, List.of()));
        List<Inventory.Board> boards = new ArrayList<>();
        for (Inventory.Board b : base.boards()) {
            List<Inventory.Item> applications = new ArrayList<>(b.applications());
            if (boards.isEmpty()) {
                tasks.forEach((name, v) -> applications.add(new Inventory.Item("sabot.task." + name, v)));
                applications.sort(Comparator.comparing(Inventory.Item::name).thenComparing(Inventory.Item::version));
            }
            boards.add(new Inventory.Board(b.name(), b.cpu(), b.bsp(), b.packages(), applications, b.libraries()));
        }
        return new Inventory(base.version(), base.uid(), base.mechanic(), boards, base.specialDevices());
    }
}
