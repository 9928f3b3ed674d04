package sabot.fleet.tests;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertTrue;

import java.util.List;

import org.jivesoftware.smack.tcp.XMPPTCPConnection;
import org.junit.jupiter.api.Test;
import org.junit.jupiter.api.extension.RegisterExtension;
import org.jxmpp.jid.EntityBareJid;

import com.google.gson.JsonObject;
import com.google.gson.JsonParser;

import sabot.testsupport.xmpp.PrivateXmppServer;

/**
 * {@code ./sabot stats} on a private Prosody (docs/STATISTICS.md): the server's own figures from its admin shell (the
 * device's session by its resource), and no archive, said as such.
 */
class ProsodyStatisticsTest {

    @RegisterExtension
    static final PrivateXmppServer XMPP = PrivateXmppServer.prosody();

    @Test
    void prosodysFiguresComeFromItsShellAndItKeepsNoArchive() throws Exception {
        EntityBareJid robotJid = XMPP.register("pstats-robot", PrivateXmppServer.DOMAIN, "pstats-pw");
        XMPPTCPConnection robot = XMPP.connect(XMPP.configuration("pstats-robot", PrivateXmppServer.DOMAIN,
                "pstats-pw").build());
        String resource = robot.getUser().getResourceOrThrow().toString();

        List<String> json = XMPP.statistics(robotJid.toString(), "--json");
        assertEquals(2, json.size(), String.join("\n", json));
        JsonObject server = JsonParser.parseString(json.get(0)).getAsJsonObject();
        assertEquals("prosody", server.get("server").getAsString());
        assertTrue(server.get("from").getAsString().startsWith("Prosody admin shell"), json.get(0));
        assertTrue(server.get("sessions").getAsInt() >= 1, json.get(0));
        assertTrue(server.get("online").getAsInt() >= 1, json.get(0));
        assertTrue(server.get("registered").getAsInt() >= 1, json.get(0));
        assertTrue(server.get("uptime_s").getAsLong() >= 0, json.get(0));
        assertEquals(resource, server.getAsJsonArray("device_sessions").get(0).getAsJsonObject().get("resource")
                .getAsString());
        JsonObject archive = JsonParser.parseString(json.get(1)).getAsJsonObject();
        assertTrue(archive.get("archive").isJsonNull(), json.get(1));
        assertTrue(archive.get("why").getAsString().contains("keeps no archive"), json.get(1));

        List<String> text = XMPP.statistics(robotJid.getLocalpart().toString());
        String all = String.join("\n", text);
        assertTrue(text.get(0).startsWith("server: prosody, up "), all);
        assertTrue(all.contains("  " + robotJid + ": sessions: " + resource), all);
        assertTrue(text.get(text.size() - 1).startsWith("archive: none; this server keeps no archive"), all);
    }
}
