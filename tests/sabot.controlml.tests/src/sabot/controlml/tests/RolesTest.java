package sabot.controlml.tests;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertFalse;
import static org.junit.jupiter.api.Assertions.assertThrows;
import static org.junit.jupiter.api.Assertions.assertTrue;

import java.nio.file.Files;
import java.util.ArrayList;
import java.util.LinkedHashMap;
import java.util.List;
import java.util.Map;

import org.junit.jupiter.api.Test;

import sabot.controlml.Resource;
import sabot.controlml.Resources;
import sabot.controlml.Role;
import sabot.controlml.payload.Goal;
import sabot.testsupport.xmpp.PrivateXmppServer;

/**
 * The role each request needs (docs/CONTROLML.md section 9): the spec's table and the catalogue agree, row for row, so
 * that neither changes alone.
 */
class RolesTest {

    @Test
    void theSpecsRoleTableIsTheCataloguesRoles() throws Exception {
        List<String> lines = Files.readAllLines(PrivateXmppServer.repositoryRoot().resolve("docs/CONTROLML.md"));
        int header = lines.indexOf("| resource | get | set |");
        assertTrue(header > 0, "no role table ('| resource | get | set |') in docs/CONTROLML.md");
        Map<String, String[]> spec = new LinkedHashMap<>();
        for (String line : lines.subList(header + 2, lines.size())) {
            if (!line.startsWith("|")) {
                break;
            }
            String[] cells = line.substring(1, line.length() - 1).split("\\|");
            spec.put(cells[0].strip().replace("`", ""), new String[] { cells[1].strip(), cells[2].strip() });
        }
        List<String> catalogue = new ArrayList<>();
        for (Resource<?, ?> r : Resources.all()) {
            catalogue.add(r.name());
            String[] row = spec.get(r.name());
            assertTrue(row != null, r.name() + " has no row in the spec's role table");
            assertEquals(r.isGettable() ? Role.OBSERVER.label() : "—", row[0], r.name() + ": get");
            assertEquals(r.isSettable() ? r.setRole().label() : "—", row[1], r.name() + ": set");
        }
        for (String name : spec.keySet()) {
            // rows the catalogue has not: another bundle's resource (cm.pid.step), or a set that needs more than its
            // resource's role (written "cm.mission maintenance")
            assertTrue(catalogue.contains(name) || name.equals("cm.pid.step") || name.equals("cm.mission maintenance"),
                    "the spec's role table names " + name + ", which is not a ControlML resource");
        }
        assertEquals("maintainer", spec.get("cm.mission maintenance")[1]);
        assertEquals("maintainer", spec.get("cm.pid.step")[1]);
    }

    @Test
    void eachSetNeedsAtLeastTheOperatorAndAnotherBundlesResourceTheMaintainerUnlessItSaysSo() {
        for (Resource<?, ?> r : Resources.all()) {
            // a lease asks for telemetry an observer receives anyway (section 6): the one set of an observer
            assertTrue(r.setRole().includes(r == Resources.TELEMETRY ? Role.OBSERVER : Role.OPERATOR), r.name());
        }
        assertEquals(Role.OBSERVER, Resources.TELEMETRY.setRole());
        assertThrows(IllegalArgumentException.class, () -> Resource.builder("cm.test.z", Goal.CODEC).settable()
                .setBy(Role.OBSERVER), "another bundle's resource: a set needs the operator at least");
        assertEquals(Role.MAINTAINER, Resource.builder("cm.test.x", Goal.CODEC).settable().build().setRole());
        assertEquals(Role.OPERATOR, Resource.builder("cm.test.y", Goal.CODEC).settable().setBy(Role.OPERATOR)
                .build().setRole());
        assertFalse(Role.OBSERVER.includes(Role.OPERATOR));
    }
}
