package sabot.identity.internal;

import java.util.ArrayList;
import java.util.List;

import org.osgi.framework.Bundle;
import org.osgi.framework.BundleContext;
import org.osgi.service.component.annotations.Activate;
import org.osgi.service.component.annotations.Component;
import org.osgi.service.component.annotations.Deactivate;

import sabot.identity.HardwareDescription;
import sabot.identity.Inventories;
import sabot.identity.Inventory;
import sabot.identity.InventorySource;

/**
 * Declarative Services component {@code sabot.identity.inventory}: the inventory of the running product, read from
 * the framework's installed bundles each time it is asked (bundles come and go with tasks).
 */
@Component(name = "sabot.identity.inventory", service = InventorySource.class)
public final class OsgiInventorySource implements InventorySource {

    private volatile BundleContext context;

    @Activate
    void activate(BundleContext ctx) {
        this.context = ctx;
    }

    @Deactivate
    void deactivate() {
        this.context = null;
    }

    @Override
    public Inventory inventory(HardwareDescription hardware) {
        BundleContext ctx = context;
        if (ctx == null) {
            throw new IllegalStateException("inventory component not active");
        }
        List<Inventory.Item> bundles = new ArrayList<>();
        Inventory.Item framework = null;
        for (Bundle b : ctx.getBundles()) {
            if (b.getSymbolicName() == null) {
                continue;
            }
            Inventory.Item item = new Inventory.Item(b.getSymbolicName(), b.getVersion().toString());
            if (b.getBundleId() == 0) {
                framework = item;
            } else {
                bundles.add(item);
            }
        }
        return Inventories.of(hardware, framework, bundles);
    }
}
