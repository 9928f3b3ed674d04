package sabot.identity;

import java.util.ArrayList;
import java.util.Comparator;
import java.util.List;

/** Builds an inventory from a list of installed software items, the way the OSGi source classifies bundles. */
public final class Inventories {

    /** Bundles whose symbolic name starts with this are Sabot's applications; the others are libraries. */
    public static final String APPLICATION_PREFIX = "sabot.";

    private Inventories() {
    }

    /**
     * @param hardware  the hardware description
     * @param framework the OSGi framework (system bundle) as a package; may be null outside OSGi
     * @param bundles   installed bundles (symbolic name, version), any order
     * @return the inventory: BSP = operating system, PACKAGE = Java runtime and framework, APPLICATION = sabot.*
     *         bundles, LIBRARY = the rest, each sorted by name
     */
    public static Inventory of(HardwareDescription hardware, Inventory.Item framework, List<Inventory.Item> bundles) {
        List<Inventory.Item> apps = new ArrayList<>();
        List<Inventory.Item> libs = new ArrayList<>();
        for (Inventory.Item b : bundles) {
            (b.name().startsWith(APPLICATION_PREFIX) ? apps : libs).add(b);
        }
        Comparator<Inventory.Item> byName = Comparator.comparing(Inventory.Item::name).thenComparing(
                Inventory.Item::version);
        apps.sort(byName);
        libs.sort(byName);
        List<Inventory.Item> packages = new ArrayList<>();
        packages.add(new Inventory.Item("java:" + System.getProperty("java.vm.name", "?"), System.getProperty(
                "java.runtime.version", "?")));
        if (framework != null) {
            packages.add(framework);
        }
        Inventory.Item bsp = new Inventory.Item(System.getProperty("os.name", "?") + " " + System.getProperty(
                "os.arch", "?"), System.getProperty("os.version", "?"));
        String cpu = System.getProperty("os.arch", "?") + " x" + Runtime.getRuntime().availableProcessors();
        return new Inventory(1, DeviceUrn.urnOf(hardware.serial()), hardware.mechanic(), List.of(new Inventory.Board(
                hardware.boardName(), cpu, bsp, packages, apps, libs)), hardware.specialDevices());
    }
}
