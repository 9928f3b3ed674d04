package sabot.testsupport.osgi;

import java.util.HashMap;
import java.util.Map;
import java.util.SortedMap;
import java.util.TreeMap;

import org.osgi.framework.Bundle;
import org.osgi.framework.BundleContext;
import org.osgi.service.metatype.AttributeDefinition;
import org.osgi.service.metatype.MetaTypeInformation;
import org.osgi.service.metatype.MetaTypeService;
import org.osgi.service.metatype.ObjectClassDefinition;
import org.osgi.util.tracker.ServiceTracker;

/** A task bundle's Metatype description as the running framework reads it (what the onboard application checks). */
public final class TaskMetatype {

    private TaskMetatype() {
    }

    /**
     * @param bundle the bundle that declares the description
     * @param pid    the configuration PID, e.g. {@code sabot.task.controlml}
     * @return each attribute's id with its first default value (null when it has none)
     * @throws AssertionError when no MetaTypeService comes within 10 s or the bundle does not describe the PID
     */
    public static Map<String, String> defaults(Bundle bundle, String pid) throws InterruptedException {
        Map<String, String> d = new HashMap<>();
        attributes(bundle, pid).forEach((id, ad) -> {
            String[] v = ad.getDefaultValue();
            d.put(id, v == null || v.length == 0 ? null : v[0]);
        });
        return d;
    }

    /**
     * @param bundle the bundle that declares the description
     * @param pid    the configuration PID, e.g. {@code sabot.task.motion}
     * @return each attribute's id with its definition, by id
     * @throws AssertionError when no MetaTypeService comes within 10 s or the bundle does not describe the PID
     */
    public static SortedMap<String, AttributeDefinition> attributes(Bundle bundle, String pid)
            throws InterruptedException {
        BundleContext context = bundle.getBundleContext();
        ServiceTracker<MetaTypeService, MetaTypeService> t = new ServiceTracker<>(context, MetaTypeService.class,
                null);
        t.open();
        try {
            MetaTypeService metaType = t.waitForService(10_000);
            if (metaType == null) {
                throw new AssertionError("no MetaTypeService within 10 s");
            }
            MetaTypeInformation info = metaType.getMetaTypeInformation(bundle);
            ObjectClassDefinition ocd = info == null ? null : info.getObjectClassDefinition(pid, null);
            if (ocd == null) {
                throw new AssertionError(bundle.getSymbolicName() + " has no Metatype description of " + pid);
            }
            SortedMap<String, AttributeDefinition> ads = new TreeMap<>();
            for (AttributeDefinition ad : ocd.getAttributeDefinitions(ObjectClassDefinition.ALL)) {
                ads.put(ad.getID(), ad);
            }
            return ads;
        } finally {
            t.close();
        }
    }
}
