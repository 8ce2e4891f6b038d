// The Properties panel's labels of FiberPLI properties with their units, e.g. "Edge Length (µm)".
#ifndef FiberPLIUnitLabels_h
#define FiberPLIUnitLabels_h

#include <QObject>

/// ParaView 5.11 makes a property's pvpython name from its XML label (every character but letters,
/// digits and '_' dropped): a label "Edge Length (µm)" would rename EdgeLength to EdgeLengthm. So
/// the XML labels stay as they are and carry no unit; a property with a unit says it in its hints,
/// `<Hints><FiberPLIUnit text="µm"/></Hints>`, and this auto-start part of the plugin's Qt side
/// appends it to the label the panel shows when that label is first shown. pvpython, pvbatch and
/// the property names are untouched; the help pages and tooltips give the units as before.
class FiberPLIUnitLabels : public QObject
{
  Q_OBJECT
public:
  void startup();
  void shutdown();

protected:
  bool eventFilter(QObject* watched, QEvent* event) override;
};

#endif
