// MeshLab adapter for the union core (filters/union).
#pragma once

#include <common/plugins/interfaces/filter_plugin.h>

class FilterSurfaceUnionPlugin : public QObject, public FilterPlugin {
  Q_OBJECT
  MESHLAB_PLUGIN_IID_EXPORTER(FILTER_PLUGIN_IID)
  Q_INTERFACES(FilterPlugin)

public:
  enum { FP_SURFACE_INTERSECTION_UNION };
  enum Source { VISIBLE_LAYERS = 0, CONNECTED_COMPONENTS = 1 };

  FilterSurfaceUnionPlugin();
  QString pluginName() const override;
  QString filterName(ActionIDType filter) const override;
  QString pythonFilterName(ActionIDType filter) const override;
  QString filterInfo(ActionIDType filter) const override;
  FilterClass getClass(const QAction* action) const override;
  FilterArity filterArity(const QAction*) const override { return VARIABLE; }
  int getPreConditions(const QAction*) const override;
  int postCondition(const QAction*) const override;
  RichParameterList initParameterList(const QAction* action, const MeshModel& m) override;
  std::map<std::string, QVariant> applyFilter(const QAction* action, const RichParameterList& params,
                                              MeshDocument& md, unsigned int& postConditionMask,
                                              vcg::CallBackPos* cb) override;
};
