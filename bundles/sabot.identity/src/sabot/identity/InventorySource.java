package sabot.identity;

import org.osgi.annotation.versioning.ProviderType;

/**
 * The inventory of the running product. The OSGi implementation (a Declarative Services component of this bundle)
 * lists the framework's actual bundles and versions.
 */
@FunctionalInterface
@ProviderType
public interface InventorySource {

    /**
     * @param hardware what the software cannot discover
     * @return the current inventory; never null
     */
    Inventory inventory(HardwareDescription hardware);
}
