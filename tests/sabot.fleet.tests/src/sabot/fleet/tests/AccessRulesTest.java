package sabot.fleet.tests;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertThrows;
import static org.junit.jupiter.api.Assertions.assertTrue;

import java.nio.file.Files;
import java.util.EnumMap;
import java.util.List;
import java.util.Map;
import java.util.Set;
import java.util.regex.Matcher;
import java.util.regex.Pattern;

import org.junit.jupiter.api.Test;
import org.jxmpp.jid.BareJid;
import org.jxmpp.jid.impl.JidCreate;

import sabot.controlml.Role;
import sabot.fleet.AccessRules;
import sabot.fleet.Enrolment;
import sabot.testsupport.xmpp.PrivateXmppServer;

/** Roles from groups, accounts and domains, without a server (the server's side: {@code FleetOnServerTest}). */
class AccessRulesTest {

    static BareJid jid(String s) throws Exception {
        return JidCreate.bareFrom(s);
    }

    @Test
    void theLabsGroupsGrantTheirRoleAndNothingElseGrantsAnything() throws Exception {
        AccessRules lab = AccessRules.labGroups();
        BareJid alice = jid("alice@sabot.local");
        assertEquals(Role.OBSERVER, lab.roleOf(alice, Set.of("sabot-observers")));
        assertEquals(Role.OPERATOR, lab.roleOf(alice, Set.of("sabot-operators")));
        assertEquals(Role.MAINTAINER, lab.roleOf(alice, Set.of("sabot-maintainers")));
        assertEquals(Role.NONE, lab.roleOf(alice, Set.of()), "deny by default");
        assertEquals(Role.NONE, lab.roleOf(alice, Set.of("friends", "Sabot-Maintainers")), "names are exact");
        assertEquals(Role.NONE, lab.roleOf(alice, Set.of(AccessRules.ROBOTS_GROUP)), "a robot has no role by being one");
        assertEquals(Role.NONE, AccessRules.none().roleOf(alice, Set.of("sabot-maintainers")));
        assertTrue(AccessRules.none().grantsNothing());
    }

    @Test
    void theHighestGrantedRoleCounts() throws Exception {
        BareJid bob = jid("bob@sabot.local");
        AccessRules rules = AccessRules.labGroups().withDomains(Role.OBSERVER, Set.of("sabot2.local")).withJid(
                Role.OPERATOR, bob);
        assertEquals(Role.MAINTAINER, rules.roleOf(bob, Set.of("sabot-observers", "sabot-maintainers")));
        assertEquals(Role.OPERATOR, rules.roleOf(bob, Set.of("sabot-observers")));
        assertEquals(Role.OBSERVER, rules.roleOf(jid("carol@sabot2.local"), Set.of()));
        assertEquals(Role.OPERATOR, rules.roleOf(jid("carol@sabot2.local"), Set.of("sabot-operators")));
        assertEquals("maintainer: groups [sabot-maintainers]; operator: groups [sabot-operators], accounts "
                + "[bob@sabot.local]; observer: groups [sabot-observers], domains [sabot2.local]", rules.describe());
    }

    @Test
    void aGrantNamesARole() throws Exception {
        IllegalArgumentException e = assertThrows(IllegalArgumentException.class, () -> AccessRules.none()
                .withGroups(Role.NONE, List.of("x")));
        assertEquals("a grant names a role: observer, operator or maintainer", e.getMessage());
        assertEquals(Role.OPERATOR, Role.ofLabel("operator"));
        assertEquals("'admin' is not a role: observer, operator or maintainer", assertThrows(
                IllegalArgumentException.class, () -> Role.ofLabel("admin")).getMessage());
        assertTrue(Role.MAINTAINER.includes(Role.OPERATOR) && !Role.OBSERVER.includes(Role.OPERATOR));
    }

    private static String shellValue(String lib, String name) {
        Matcher m = Pattern.compile("(?m)^" + name + "=(\\S+)$").matcher(lib);
        assertTrue(m.find(), "no " + name + " in lib.sh");
        return m.group(1);
    }

    /**
     * The shell's names of the lab's groups and the enrolment token's prefix (product/bin/lib.sh: ./sabot xmpp grant,
     * ./sabot enrol, the demo) are these.
     */
    @Test
    void theScriptsGroupNamesAreTheRules() throws Exception {
        String lib = Files.readString(PrivateXmppServer.repositoryRoot().resolve("product/bin/lib.sh"));
        Matcher robots = Pattern.compile("(?m)^SABOT_GROUP_ROBOTS=(\\S+)$").matcher(lib);
        assertTrue(robots.find(), "no SABOT_GROUP_ROBOTS in lib.sh");
        assertEquals(AccessRules.ROBOTS_GROUP, robots.group(1));
        assertEquals(AccessRules.ENROLLING_GROUP, shellValue(lib, "SABOT_GROUP_ENROLLING"));
        assertEquals(Enrolment.TOKEN_PREFIX, shellValue(lib, "SABOT_ENROL_TOKEN_PREFIX"));
        Matcher roles = Pattern.compile("(?m)^declare -A SABOT_ROLE_GROUPS=\\((.*)\\)$").matcher(lib);
        assertTrue(roles.find(), "no SABOT_ROLE_GROUPS in lib.sh");
        Map<Role, String> script = new EnumMap<>(Role.class);
        Matcher pair = Pattern.compile("\\[(\\w+)]=(\\S+)").matcher(roles.group(1));
        while (pair.find()) {
            script.put(Role.ofLabel(pair.group(1)), pair.group(2));
        }
        assertEquals(AccessRules.LAB_GROUPS, script);
    }
}
