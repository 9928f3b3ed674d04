package sabot.controlml.swe;

import org.osgi.annotation.versioning.ProviderType;

/**
 * The subset of the OGC SWE Common Data Model 2.0 (namespace {@value Swe#NAMESPACE}) that ControlML payloads use:
 * scalar components ({@link Quantity}, {@link Count}, {@link Time}, {@link Text}, {@link Category},
 * {@link SweBoolean}) and the block components {@link DataRecord} and {@link DataArray}. Instances are immutable;
 * {@link SweXml} reads and writes them.
 */
@ProviderType
public sealed interface SweComponent permits Quantity, Count, Time, Text, Category, SweBoolean, DataRecord, DataArray {

    /** @return the element name in the SWE namespace, e.g. {@code Quantity} */
    String elementName();
}
