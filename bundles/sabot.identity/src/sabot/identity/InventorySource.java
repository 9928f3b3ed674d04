package sabot.identity;

/**
 * The inventory of the running product. The OSGi implementation (a Declarative Services component of this bundle)
 * lists the framework's actual bundles and versions.
 */
@FunctionalInterface
public interface InventorySource {

    /**
     * @param hardware what the software cannot discover
     * @return the current inventory; never null
     */
    Inventory inventory(HardwareDescription hardware);
}
