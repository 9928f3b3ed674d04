package sabot.onboard.internal;

import java.util.ArrayList;
import java.util.LinkedHashMap;
import java.util.List;
import java.util.Map;
import java.util.TreeMap;

import org.eclipse.equinox.metatype.EquinoxAttributeDefinition;
import org.osgi.framework.Bundle;
import org.osgi.framework.BundleContext;
import org.osgi.service.component.runtime.ServiceComponentRuntime;
import org.osgi.service.component.runtime.dto.ComponentDescriptionDTO;
import org.osgi.service.metatype.AttributeDefinition;
import org.osgi.service.metatype.MetaTypeInformation;
import org.osgi.service.metatype.MetaTypeService;
import org.osgi.service.metatype.ObjectClassDefinition;

import sabot.onboard.config.SettingForm;
import sabot.onboard.config.TaskForm;
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

    /** @return every installed task's form (its Metatype's names, descriptions, defaults, options), without values */
    static List<TaskForm> forms(BundleContext context, ServiceComponentRuntime scr, MetaTypeService metaType) {
        Map<String, TaskForm> forms = new TreeMap<>();
        for (ComponentDescriptionDTO component : scr.getComponentDescriptionDTOs()) {
            if (!component.name.startsWith(OnboardTask.PID_PREFIX)) {
                continue;
            }
            String task = component.name.substring(OnboardTask.PID_PREFIX.length());
            List<SettingForm> settings = new ArrayList<>();
            String title = task;
            String description = "";
            Bundle bundle = context.getBundle(component.bundle.id);
            MetaTypeInformation info = bundle == null ? null : metaType.getMetaTypeInformation(bundle);
            if (info != null && contains(info.getPids(), component.name)) {
                ObjectClassDefinition ocd = info.getObjectClassDefinition(component.name, null);
                title = ocd.getName() == null || ocd.getName().isBlank() ? task : ocd.getName();
                description = ocd.getDescription() == null ? "" : ocd.getDescription();
                AttributeDefinition[] ads = ocd.getAttributeDefinitions(ObjectClassDefinition.ALL);
                AttributeDefinition[] required = ocd.getAttributeDefinitions(ObjectClassDefinition.REQUIRED);
                if (ads != null) {
                    for (AttributeDefinition ad : ads) {
                        settings.add(form(ad, contains(required, ad)));
                    }
                }
            }
            forms.put(task, new TaskForm(task, title, description, false, settings));
        }
        return List.copyOf(forms.values());
    }

    private static SettingForm form(AttributeDefinition ad, boolean required) {
        SettingSpec spec = SettingSpec.of(ad, required);
        String min = null;
        String max = null;
        if (ad instanceof EquinoxAttributeDefinition eq) {
            min = eq.getMin() == null || eq.getMin().isBlank() ? null : eq.getMin().strip();
            max = eq.getMax() == null || eq.getMax().isBlank() ? null : eq.getMax().strip();
        }
        String[] defaults = ad.getDefaultValue();
        List<SettingForm.Option> options = new ArrayList<>();
        String[] values = ad.getOptionValues();
        String[] labels = ad.getOptionLabels();
        if (values != null) {
            for (int i = 0; i < values.length; i++) {
                options.add(new SettingForm.Option(values[i], labels != null && i < labels.length ? labels[i]
                        : values[i]));
            }
        }
        return new SettingForm(ad.getID(), ad.getName() == null || ad.getName().isBlank() ? ad.getID() : ad.getName(),
                ad.getDescription() == null ? "" : ad.getDescription(), typeName(ad.getType()), min, max,
                defaults == null || defaults.length == 0 ? null : String.join(",", defaults), options, spec.mandatory(),
                null);
    }

    private static String typeName(int type) {
        return switch (type) {
            case AttributeDefinition.INTEGER -> "integer";
            case AttributeDefinition.LONG -> "long";
            case AttributeDefinition.DOUBLE -> "double";
            case AttributeDefinition.FLOAT -> "float";
            case AttributeDefinition.BOOLEAN -> "boolean";
            default -> "string";
        };
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
