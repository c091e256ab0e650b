"""Loads terratin's plugin from a QGIS profile the way QGIS does (qgis.utils: find the plugins
of the profile's python/plugins folder, import the package, classFactory, initProcessing) and
prints what the Processing registry then holds. Run in its own process by test_processing.py,
so that the plugin comes from the profile and not from PYTHONPATH.

usage: plugin_install_check.py PROFILE_FOLDER
"""

import os
import sys

os.environ.setdefault("QT_QPA_PLATFORM", "offscreen")

from qgis.core import QgsApplication  # noqa: E402
from qgis.PyQt.QtCore import QSettings  # noqa: E402

profile = sys.argv[1]
QSettings.setPath(QSettings.NativeFormat, QSettings.UserScope, os.path.join(profile, "settings"))
QgsApplication.setPrefixPath("/usr", True)
application = QgsApplication([], False, profile)
application.initQgis()
sys.path.append("/usr/share/qgis/python/plugins")
from processing.core.Processing import Processing  # noqa: E402

import qgis.utils  # noqa: E402

Processing.initialize()
# QGIS puts each profile's plugin folder on sys.path and into plugin_paths at start-up.
plugins = os.path.join(profile, "python", "plugins")
sys.path.insert(0, plugins)
qgis.utils.plugin_paths = [plugins]
qgis.utils.updateAvailablePlugins()
print("available:", " ".join(qgis.utils.available_plugins))
print("processing provider:", qgis.utils.pluginMetadata("terratin_processing", "hasProcessingProvider"))
if not (qgis.utils.loadPlugin("terratin_processing")
        and qgis.utils.startProcessingPlugin("terratin_processing")):
    sys.exit("the plugin does not start")
registry = QgsApplication.processingRegistry()
print("from:", os.path.dirname(sys.modules["terratin_processing"].__file__))
print("algorithms:", " ".join(sorted(a.id() for a in registry.providerById("terratin").algorithms())))
qgis.utils.unloadPlugin("terratin_processing")
print("after unload:", registry.providerById("terratin"))
