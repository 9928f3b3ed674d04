package sabot.fleet.internal;

import java.nio.charset.StandardCharsets;
import java.util.List;

import javax.security.auth.callback.CallbackHandler;

import org.jivesoftware.smack.SmackException.SmackSaslException;
import org.jivesoftware.smack.sasl.SASLMechanism;

import com.ongres.scram.client.ScramClient;
import com.ongres.scram.common.exception.ScramException;

/**
 * SCRAM-SHA-256 (RFC 7677) for Smack 4.4, whose own SCRAM is SHA-1 only (its {@code ScramMechanism} computes the
 * stored key with SHA-1 whatever the HMAC): the exchange is the ongres scram-client library's (the SCRAM of
 * PostgreSQL's JDBC driver), adapted here to Smack's SASL mechanism. The password never crosses the link; the server's
 * signature in its final message is checked, so a server that does not know the password is not taken for ours.
 * Without channel binding (gs2 flag {@code n}): the -PLUS variant needs a binding both ends implement, and Prosody 0.12
 * binds only {@code tls-unique}, which TLS 1.3 does not have.
 */
public final class ScramSha256Mechanism extends SASLMechanism {

    /** The mechanism's name. */
    public static final String NAME = "SCRAM-SHA-256";
    /** Ahead of Smack's SCRAM-SHA-1 (110) and PLAIN (400): a lower number is preferred. */
    public static final int PRIORITY = 105;

    private ScramClient client;
    private boolean serverFirstReceived;
    private boolean serverVerified;

    @Override
    protected void authenticateInternal(CallbackHandler cbh) throws SmackSaslException {
        throw new SmackSaslException(NAME + " needs the account's password, not a callback handler");
    }

    @Override
    protected byte[] getAuthenticationText() throws SmackSaslException {
        try {
            ScramClient.FinalBuildStage builder = ScramClient.builder().advertisedMechanisms(List.of(NAME))
                    .username(authenticationId).password(password.toCharArray());
            if (authorizationId != null) {
                builder = builder.authzid(authorizationId.toString());
            }
            client = builder.build();
            return toBytes(client.clientFirstMessage().toString());
        } catch (IllegalArgumentException e) {
            throw new SmackSaslException(NAME + ": " + e.getMessage());
        }
    }

    @Override
    protected byte[] evaluateChallenge(byte[] challenge) throws SmackSaslException {
        String message = new String(challenge, StandardCharsets.UTF_8);
        try {
            if (!serverFirstReceived) {
                serverFirstReceived = true;
                client.serverFirstMessage(message);
                return toBytes(client.clientFinalMessage().toString());
            }
            client.serverFinalMessage(message);
            serverVerified = true;
            return null;
        } catch (ScramException | IllegalArgumentException | IllegalStateException e) {
            throw new SmackSaslException(NAME + ": " + e.getMessage());
        }
    }

    @Override
    protected void checkIfSuccessfulOrThrow() throws SmackSaslException {
        if (!serverVerified) {
            throw new SmackSaslException(NAME + ": the server's final message (its proof that it knows the password) "
                    + "did not come or did not match");
        }
    }

    @Override
    public String getName() {
        return NAME;
    }

    @Override
    public int getPriority() {
        return PRIORITY;
    }

    @Override
    public boolean authzidSupported() {
        return true;
    }

    @Override
    protected SASLMechanism newInstance() {
        return new ScramSha256Mechanism();
    }
}
