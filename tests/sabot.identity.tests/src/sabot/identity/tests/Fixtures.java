package sabot.identity.tests;

import java.net.URI;
import java.time.LocalDate;
import java.util.ArrayList;
import java.util.List;

import sabot.identity.DeviceProfile;
import sabot.identity.DeviceUrn;
import sabot.identity.HardwareDescription;
import sabot.identity.Inventories;
import sabot.identity.Inventory;

final class Fixtures {

    static final String SERIAL = "SBT-2026-0042";

    static HardwareDescription hardware(String serial) {
        return new HardwareDescription(serial, new Inventory.Mechanic("sabot-reference", List.of(new Inventory.Part(
                "wheel.radius", "0.075 m"), new Inventory.Part("track.width", "0.40 m"), new Inventory.Part(
                        "gear.ratio", "43"), new Inventory.Part("encoder.lines", "512"))), "embedded-pc", List.of(
                                new Inventory.SpecialDevice("SACT motor board", "SACT-2", "RS485", "0x14"),
                                new Inventory.SpecialDevice("INS board", "INS-1", "RS485", "0x15"),
                                new Inventory.SpecialDevice("sonar ring", "SON-8", "RS485", "0x16")));
    }

    static Inventory inventory(int libraries) {
        List<Inventory.Item> bundles = new ArrayList<>();
        bundles.add(new Inventory.Item("sabot.onboard", "0.1.0.202611210800"));
        bundles.add(new Inventory.Item("sabot.controlml", "0.1.0.202611210800"));
        for (int i = 0; i < libraries; i++) {
            bundles.add(new Inventory.Item("org.example.library" + i, "1." + i + ".0.v2026" + (1000 + i)));
        }
        return Inventories.of(hardware(SERIAL), new Inventory.Item("org.eclipse.osgi", "3.24.300.v20260721-1251"),
                bundles);
    }

    static DeviceProfile profile(String jid) {
        return new DeviceProfile("mobile robot (differential drive)", "Sabot Robotics", "R2", "sabot-42", URI.create(
                "http://sabot-42.lab.example/config"), 45.7640426, 4.8356591, DeviceUrn.urnOf(SERIAL), jid, "robot",
                LocalDate.of(2026, 11, 21), new DeviceProfile.SupportContact("Lab support", "1 rue de la Robotique",
                        "Lyon", "69007", "France", "+33 4 00 00 00 00"), "Reference robot of the Sabot lab");
    }

    private Fixtures() {
    }
}
