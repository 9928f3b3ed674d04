package sabot.fleet.tests;

import org.jivesoftware.smack.roster.Roster;
import org.jivesoftware.smack.tcp.XMPPTCPConnection;
import org.jxmpp.jid.EntityBareJid;

import sabot.controlml.AccessPolicy;
import sabot.controlml.Role;
import sabot.fleet.AccessRules;
import sabot.testsupport.xmpp.PrivateXmppServer;

/**
 * A lab on a server with the archive (docs/ARCHIVE.md), for the tests that read it: a goal-serving robot of the lab
 * ({@link FleetOnServerTest#goalDevice}), an operator and an observer whose roles the robot has seen, and a stranger;
 * each logged in, their accounts named {@code PREFIX-robot}, {@code PREFIX-operator}, ...
 */
record ArchiveLab(EntityBareJid robotJid, EntityBareJid operatorJid, EntityBareJid observerJid,
        XMPPTCPConnection robot, XMPPTCPConnection operator, XMPPTCPConnection observer,
        XMPPTCPConnection stranger) {

    static ArchiveLab on(PrivateXmppServer xmpp, String prefix, String password) throws Exception {
        EntityBareJid robotJid = xmpp.register(prefix + "-robot", PrivateXmppServer.DOMAIN, password);
        EntityBareJid operatorJid = xmpp.register(prefix + "-operator", PrivateXmppServer.DOMAIN, password);
        EntityBareJid observerJid = xmpp.register(prefix + "-observer", PrivateXmppServer.DOMAIN, password);
        xmpp.register(prefix + "-stranger", PrivateXmppServer.DOMAIN, password);
        XMPPTCPConnection robot = login(xmpp, prefix + "-robot", password);
        XMPPTCPConnection operator = login(xmpp, prefix + "-operator", password);
        XMPPTCPConnection observer = login(xmpp, prefix + "-observer", password);
        XMPPTCPConnection stranger = login(xmpp, prefix + "-stranger", password);
        AccessPolicy policy = AccessRules.labGroups().on(robot);
        FleetOnServerTest.goalDevice(robot, policy);
        xmpp.enrolRobot(robotJid);
        xmpp.grant(operatorJid, Role.OPERATOR);
        xmpp.grant(observerJid, Role.OBSERVER);
        FleetOnServerTest.awaitRole(Roster.getInstanceFor(robot), policy, operator, Role.OPERATOR);
        FleetOnServerTest.awaitRole(Roster.getInstanceFor(robot), policy, observer, Role.OBSERVER);
        return new ArchiveLab(robotJid, operatorJid, observerJid, robot, operator, observer, stranger);
    }

    private static XMPPTCPConnection login(PrivateXmppServer xmpp, String localpart, String password)
            throws Exception {
        return xmpp.connect(xmpp.configuration(localpart, PrivateXmppServer.DOMAIN, password).build());
    }
}
