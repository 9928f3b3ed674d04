package sabot.onboard.internal;

import java.util.LinkedHashMap;
import java.util.Map;
import java.util.TreeMap;

import org.osgi.framework.Bundle;
import org.osgi.framework.BundleContext;
import org.osgi.service.component.runtime.ServiceComponentRuntime;
import org.osgi.service.component.runtime.dto.ComponentDescriptionDTO;
import org.osgi.service.metatype.AttributeDefinition;
import org.osgi.service.metatype.MetaTypeInformation;
import org.osgi.service.metatype.MetaTypeService;
import org.osgi.service.metatype.ObjectClassDefinition;

import sabot.onboard.task.OnboardTask;

/** The tasks installed in this product: DS components named {@code sabot.task.*}, with their Metatype settings. */
final class OsgiTaskCatalog {

    private OsgiTaskCatalog() {
    }

    /** @return task name to its settings by id (a task without a Metatype description has no settings) */
    static Map<String, Map<String, SettingSpec>> read(BundleContext context, ServiceComponentRuntime scr,
            MetaTypeService metaType) {
        Map<String, Map<String, SettingSpec>> catalog = new TreeMap<>();
        for (ComponentDescriptionDTO component : scr.getComponentDescriptionDTOs()) {
            if (!component.name.startsWith(OnboardTask.PID_PREFIX)) {
                continue;
            }
            String task = component.name.substring(OnboardTask.PID_PREFIX.length());
            Map<String, SettingSpec> settings = new LinkedHashMap<>();
            Bundle bundle = context.getBundle(component.bundle.id);
            MetaTypeInformation info = bundle == null ? null : metaType.getMetaTypeInformation(bundle);
            if (info != null && contains(info.getPids(), component.name)) {
                ObjectClassDefinition ocd = info.getObjectClassDefinition(component.name, null);
                AttributeDefinition[] ads = ocd.getAttributeDefinitions(ObjectClassDefinition.ALL);
                AttributeDefinition[] required = ocd.getAttributeDefinitions(ObjectClassDefinition.REQUIRED);
                if (ads != null) {
                    for (AttributeDefinition ad : ads) {
                        settings.put(ad.getID(), SettingSpec.of(ad, contains(required, ad)));
                    }
                }
            }
            catalog.put(task, settings);
        }
        return catalog;
    }

    private static boolean contains(AttributeDefinition[] ads, AttributeDefinition ad) {
        if (ads != null) {
            for (AttributeDefinition a : ads) {
                if (a.getID().equals(ad.getID())) {
                    return true;
                }
            }
        }
        return false;
    }

    private static boolean contains(String[] pids, String pid) {
        if (pids != null) {
            for (String p : pids) {
                if (p.equals(pid)) {
                    return true;
                }
            }
        }
        return false;
    }
}
