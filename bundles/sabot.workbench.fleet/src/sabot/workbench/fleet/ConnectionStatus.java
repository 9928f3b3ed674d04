package sabot.workbench.fleet;

import java.time.Instant;
import java.util.Objects;

/**
 * The state of the workbench's one XMPP connection.
 *
 * @param state   what the connection is doing; never null
 * @param account the bare JID it connects as, or the empty string without an account; never null
 * @param detail  for the operator: the server and port, why it is not connected, when it tries again; never null
 * @param since   when it entered this state (workbench clock); never null
 */
public record ConnectionStatus(State state, String account, String detail, Instant since) {

    /** The connection's states. */
    public enum State {
        /** no complete account in the preferences (or no password stored) */
        NO_ACCOUNT,
        /** connecting and logging in */
        CONNECTING,
        /** logged in: robots and telemetry are live */
        ONLINE,
        /** the last attempt failed or the connection dropped; the next attempt is scheduled (back-off) */
        RETRYING,
        /** the plug-in stopped */
        STOPPED
    }

    public ConnectionStatus {
        Objects.requireNonNull(state, "state");
        Objects.requireNonNull(account, "account");
        Objects.requireNonNull(detail, "detail");
        Objects.requireNonNull(since, "since");
    }

    /** @return a one-line text for the status line, e.g. {@code operator@sabot.local: online} */
    public String summary() {
        String what = switch (state) {
            case NO_ACCOUNT -> "no XMPP account (Window > Preferences > XMPP Account)";
            case CONNECTING -> "connecting";
            case ONLINE -> "online";
            case RETRYING -> "offline";
            case STOPPED -> "stopped";
        };
        String head = account.isEmpty() ? what : account + ": " + what;
        return detail.isEmpty() ? head : head + " (" + detail + ")";
    }
}
