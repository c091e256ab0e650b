"""The terrain style on the TIN layer Processing loads when the algorithm has finished.

terratin writes the style as <output>.qml, which QGIS reads as the layer's default style. But
Processing then applies its own "Style for polygon layers" (Settings > Options > Processing >
General) where the user set one, over the default; a layer post-processor runs after that and
loads the .qml again.
"""

import os

from qgis.core import QgsProcessingLayerPostProcessorInterface

# QGIS takes the post-processor, yet sip lets its Python half go unless Python keeps a reference
# (the known workaround; without it the style test fails). One per output: a later run on the
# same file replaces it.
_loaders = {}


class TerrainStyleLoader(QgsProcessingLayerPostProcessorInterface):
    def __init__(self, style_path):
        super().__init__()
        self.style_path = style_path

    def postProcessLayer(self, layer, context, feedback):  # noqa: N802 (QGIS's name)
        message, loaded = layer.loadNamedStyle(self.style_path)
        if not loaded:
            if feedback is not None:
                feedback.pushWarning(
                    f"terratin: the terrain style {self.style_path} is not applied: {message}"
                )
            return
        layer.triggerRepaint()


def style_path(output):
    """Where terratin writes the style of `output` (its --qgis-style): beside it, as .qml."""
    return os.path.splitext(output)[0] + ".qml"


def apply_terrain_style_on_load(output, context):
    """Have Processing give the layer of `output` the terrain style when it loads it (only
    when it loads it: processing.run alone loads nothing)."""
    if not context.willLoadLayerOnCompletion(output):
        return
    loader = TerrainStyleLoader(style_path(output))
    _loaders[output] = loader
    context.layerToLoadOnCompletionDetails(output).setPostProcessor(loader)
