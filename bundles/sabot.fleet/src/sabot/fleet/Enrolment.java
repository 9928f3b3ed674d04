package sabot.fleet;

import java.security.SecureRandom;
import java.util.HexFormat;

import org.jivesoftware.smack.SmackException;
import org.jivesoftware.smack.XMPPConnection;
import org.jivesoftware.smack.XMPPException;
import org.jivesoftware.smackx.iqregister.AccountManager;

/**
 * A robot's enrolment (docs/SECURITY.md, "Enrolment"): the lab makes its account with a one-time token as the
 * password ({@code ./sabot enrol token JID}), in the quarantine group {@link AccessRules#ENROLLING_GROUP}; the
 * technician writes the token into the robot's password file; at its first login the robot replaces the token with a
 * password of its own ({@link #replaceToken}: XEP-0077 password change), so that the token is good for one login and
 * the robot's secret never leaves it; the lab then approves it ({@code ./sabot enrol approve JID}: the robots' group)
 * or refuses it (its account deleted). In the quarantine a robot sees no group, so it finds no role anywhere
 * ({@link AccessRules}) and obeys nobody; the accounts of the lab see it asking for access.
 */
public final class Enrolment {

    /** What every token begins with (product/bin/lib.sh {@code SABOT_ENROL_TOKEN_PREFIX}: the same). */
    public static final String TOKEN_PREFIX = "sabot-enrol-";
    private static final int PASSWORD_BYTES = 24;
    private static final SecureRandom RANDOM = new SecureRandom();

    private Enrolment() {
    }

    /** @return whether a password is an enrolment token (to be replaced at the first login) */
    public static boolean isToken(String password) {
        return password != null && password.startsWith(TOKEN_PREFIX);
    }

    /** @return a new random password (192 bits, hexadecimal): never a token */
    public static String newPassword() {
        byte[] bytes = new byte[PASSWORD_BYTES];
        RANDOM.nextBytes(bytes);
        return HexFormat.of().formatHex(bytes);
    }

    /**
     * Replaces the logged-in account's password (an enrolment token) with {@code password}, over the connection's
     * TLS stream (XEP-0077 password change; in-band registration of new accounts stays closed).
     *
     * @throws FleetException when the server refuses (its condition in the message) or does not answer
     */
    public static void replaceToken(XMPPConnection connection, String password) throws FleetException,
            InterruptedException {
        if (isToken(password)) {
            throw new IllegalArgumentException("the new password must not be a token");
        }
        try {
            AccountManager.getInstance(connection).changePassword(password);
        } catch (XMPPException.XMPPErrorException e) {
            throw new FleetException("the server refused to replace the enrolment token of " + connection.getUser()
                    .asBareJid() + ": " + e.getStanzaError().getCondition(), e);
        } catch (SmackException e) {
            throw new FleetException("replacing the enrolment token of " + connection.getUser().asBareJid()
                    + " failed: " + e.getMessage(), e);
        }
    }
}
