/**
 * Pictures of a plan: costmap, navigation function and path rendered to an image or PNG file with
 * {@code javax.imageio} (no SWT, so it runs headless and in the docs build).
 */
package sabot.tools.render;
