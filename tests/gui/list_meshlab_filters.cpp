// Headless check of what MeshLab 2025.07 itself loads: MeshLab's own PluginManager (the code
// the desktop application runs at start-up) loads every plugin of the given folders and this
// prints one line per filter: plugin, python name, menu name, filter class bits, parameters.
// Needs no display: a QCoreApplication is enough for filter plugins.
#include <common/globals.h>
#include <common/ml_document/mesh_document.h>
#include <common/plugins/plugin_manager.h>
#include <vcg/complex/algorithms/create/platonic.h>

#include <QCoreApplication>
#include <QDir>

#include <cstdio>

int main(int argc, char** argv) {
  QCoreApplication app(argc, argv);
  if (argc < 2) {
    std::fprintf(stderr, "usage: %s PLUGIN_DIR...\n", argv[0]);
    return 2;
  }
  PluginManager& pm = meshlab::pluginManagerInstance();
  for (int i = 1; i < argc; ++i) {
    try {
      pm.loadPlugins(QDir(QString::fromLocal8Bit(argv[i])));
    } catch (const MLException& e) {
      std::fprintf(stderr, "error loading plugins from %s: %s\n", argv[i], e.what());
      return 1;
    }
  }
  MeshDocument md;  // a dummy cube, like MeshLab's registration pass
  MeshModel* m = md.addNewMesh("", "cube");
  vcg::tri::Hexahedron(m->cm);
  for (FilterPlugin* fp : pm.filterPluginIterator()) {
    for (QAction* a : fp->actions()) {
      RichParameterList params = fp->initParameterList(a, md);
      std::printf("%s\t%s\t%s\t%d\t%d\n", qUtf8Printable(fp->pluginName()),
                  qUtf8Printable(fp->pythonFilterName(a)), qUtf8Printable(fp->filterName(a)),
                  int(fp->getClass(a)), int(params.size()));
    }
  }
  return 0;
}
