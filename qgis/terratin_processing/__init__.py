"""terratin's QGIS plugin: the Processing provider "terratin" (docs/qgis.md)."""


def classFactory(iface):  # noqa: N802 (QGIS's name)
    from .plugin import TerratinProcessingPlugin

    return TerratinProcessingPlugin(iface)
