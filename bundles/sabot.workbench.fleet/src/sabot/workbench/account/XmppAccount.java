package sabot.workbench.account;

/**
 * The operator's XMPP account as the workbench connects with it. The password is not part of this value: it lives
 * only in the secret file of {@link XmppAccountStore}.
 *
 * @param server host name or address of the XMPP server (may differ from the JID's domain); several, comma-separated
 *               without spaces, for the nodes of a cluster on one port ({@link #servers()}: tried in turn)
 * @param port   client port, 1..65535 (XMPP's default is 5222)
 * @param jid    bare JID, {@code local@domain}
 * @param caFile PEM file of the CA that signs the server's certificate (a lab CA); "" for the JVM's default trust
 *               store. The connection always requires TLS.
 */
public record XmppAccount(String server, int port, String jid, String caFile) {

    /** An account whose server has a publicly signed certificate (the JVM's default trust store). */
    public XmppAccount(String server, int port, String jid) {
        this(server, port, jid, "");
    }

    /** Default client port of XMPP (RFC 6120). */
    public static final int DEFAULT_PORT = 5222;

    public XmppAccount {
        server = server == null ? "" : server.strip();
        jid = jid == null ? "" : jid.strip();
        caFile = caFile == null ? "" : caFile.strip();
    }

    /** @return the server's names or addresses: one, or a cluster's nodes in the order they are tried */
    public java.util.List<String> servers() {
        return java.util.List.of(server.split(",", -1));
    }

    /**
     * @return null when the account is complete and well-formed, else a message for the operator naming the field
     */
    public String problem() {
        if (server.isEmpty()) {
            return "Server is empty";
        }
        if (server.chars().anyMatch(Character::isWhitespace)) {
            return "Server must not contain spaces";
        }
        if (servers().stream().anyMatch(String::isEmpty)) {
            return "Server: an empty name in the list (several servers are comma-separated: a,b)";
        }
        if (port < 1 || port > 65535) {
            return "Port must be between 1 and 65535";
        }
        int at = jid.indexOf('@');
        if (at <= 0 || at == jid.length() - 1 || jid.indexOf('@', at + 1) >= 0 || jid.contains("/")
                || jid.chars().anyMatch(Character::isWhitespace)) {
            return "JID must look like name@domain (no resource, no spaces)";
        }
        if (!caFile.isEmpty() && !java.nio.file.Files.isReadable(java.nio.file.Path.of(caFile))) {
            return "CA file " + caFile + " cannot be read";
        }
        return null;
    }
}
