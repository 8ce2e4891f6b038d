#include "FiberPLIUnitLabels.h"

#include <pqPropertyWidget.h>
#include <pqProxyWidget.h>

#include <vtkPVXMLElement.h>
#include <vtkSMProperty.h>
#include <vtkSMPropertyIterator.h>
#include <vtkSMProxy.h>
#include <vtkSmartPointer.h>

#include <QCoreApplication>
#include <QEvent>
#include <QLabel>
#include <QTextDocumentFragment>

namespace
{
const char* const kDone = "fiberpliLabelled"; // a label is rewritten once

QString unitOf(vtkSMProperty* property)
{
  vtkPVXMLElement* hints = property ? property->GetHints() : nullptr;
  vtkPVXMLElement* unit = hints ? hints->FindNestedElementByName("FiberPLIUnit") : nullptr;
  return unit && unit->GetAttribute("text") ? QString::fromUtf8(unit->GetAttribute("text"))
                                            : QString();
}

// The property of `proxy` whose panel label is `text`, if it has a unit.
vtkSMProperty* propertyLabelled(vtkSMProxy* proxy, const QString& text)
{
  vtkSmartPointer<vtkSMPropertyIterator> it;
  it.TakeReference(proxy->NewPropertyIterator());
  for (it->Begin(); !it->IsAtEnd(); it->Next())
  {
    vtkSMProperty* property = it->GetProperty();
    if (property && property->GetXMLLabel() && text == QString::fromUtf8(property->GetXMLLabel()) &&
      !unitOf(property).isEmpty())
    {
      return property;
    }
  }
  return nullptr;
}

// The label beside a property's widget: a QLabel child of the panel, "<p>Edge Length</p>".
void labelBesideWidget(QLabel* label, pqProxyWidget* panel)
{
  const QString plain = QTextDocumentFragment::fromHtml(label->text()).toPlainText().trimmed();
  if (vtkSMProperty* property = propertyLabelled(panel->proxy(), plain))
  {
    QString text = label->text();
    const int at = text.indexOf(plain);
    text.insert(at + plain.size(), " (" + unitOf(property) + ")");
    label->setText(text);
  }
}

// A list property (RotationAngles, …) gets no label beside it in ParaView 5.11: its widget shows
// only "Value Range: [min, max]" above the table. That line gets the property's name and unit.
void labelInsideList(QLabel* label, vtkSMProperty* property)
{
  const QString unit = unitOf(property);
  if (!property->GetXMLLabel() || unit.isEmpty() || !label->text().contains("Value Range"))
  {
    return;
  }
  const QString range = QTextDocumentFragment::fromHtml(label->text()).toPlainText().trimmed();
  label->setText(QString("<html><b>%1 (%2)</b> %3</html>")
                   .arg(QString::fromUtf8(property->GetXMLLabel()).toHtmlEscaped(),
                     unit.toHtmlEscaped(), range.toHtmlEscaped()));
}
} // namespace

void FiberPLIUnitLabels::startup()
{
  QCoreApplication::instance()->installEventFilter(this);
}

void FiberPLIUnitLabels::shutdown()
{
  if (QCoreApplication* app = QCoreApplication::instance())
  {
    app->removeEventFilter(this);
  }
}

bool FiberPLIUnitLabels::eventFilter(QObject* watched, QEvent* event)
{
  // Labels are shown when the panel lays them out; only FiberPLI's properties have FiberPLIUnit.
  if (event->type() == QEvent::Show)
  {
    auto* label = qobject_cast<QLabel*>(watched);
    if (label && !label->property(kDone).toBool())
    {
      if (auto* panel = qobject_cast<pqProxyWidget*>(label->parentWidget()))
      {
        label->setProperty(kDone, true);
        if (panel->proxy())
        {
          labelBesideWidget(label, panel);
        }
      }
      else
      {
        // The list's own widget may be nested in the property's widget: the nearest one that
        // knows its property.
        for (QWidget* up = label->parentWidget(); up && !qobject_cast<pqProxyWidget*>(up);
             up = up->parentWidget())
        {
          auto* widget = qobject_cast<pqPropertyWidget*>(up);
          if (widget && widget->property())
          {
            label->setProperty(kDone, true);
            labelInsideList(label, widget->property());
            break;
          }
        }
      }
    }
  }
  return QObject::eventFilter(watched, event);
}
