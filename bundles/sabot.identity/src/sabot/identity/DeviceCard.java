package sabot.identity;

/**
 * What another client learns about a device from its vCard.
 *
 * @param profile   the profile; never null
 * @param inventory the inventory decoded from the PHOTO's QR code; null when the vCard has no readable one (see
 *                  {@code inventoryProblem})
 * @param inventoryProblem why there is no inventory, or null
 */
public record DeviceCard(DeviceProfile profile, Inventory inventory, String inventoryProblem) {
}
