package sabot.controlml;

import java.util.concurrent.CompletableFuture;

/**
 * A command sent as a {@code <message/>} to a device's bare JID (delivered when it comes online).
 *
 * @param id      the command's ControlML id
 * @param outcome completes when the device's answer arrives (a message, possibly while this client was away and
 *                delivered from its offline store); it does not time out by itself
 * @param <T>     the resource's value
 */
public record PendingCommand<T>(RequestId id, CompletableFuture<Outcome<T>> outcome) {
}
