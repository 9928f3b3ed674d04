/** Planar geometry shared by every Sabot bundle: SI units (metres, seconds) and radians throughout. */
package sabot.model.geometry;
