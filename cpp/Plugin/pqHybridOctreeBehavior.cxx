#include "pqHybridOctreeBehavior.h"

#include "pqApplicationCore.h"
#include "pqDisplayColorWidget.h"
#include "pqRepresentation.h"
#include "pqServerManagerModel.h"
#include "pqUndoStack.h"
#include "pqView.h"
#include "vtkCommand.h"
#include "vtkDataObject.h"
#include "vtkEventQtSlotConnect.h"
#include "vtkSMArrayListDomain.h"
#include "vtkSMPVRepresentationProxy.h"
#include "vtkSMProperty.h"
#include "vtkSMPropertyHelper.h"
#include "vtkSMSessionProxyManager.h"
#include "vtkSMViewProxy.h"

#include <QTimer>

#include <cstring>

namespace
{
/// A property only our extension adds to ParaView's image representation.
const char* const OwnProperty = "TextureBudgetMB";

/// How long after a frame with bricks still loading the view draws again.
const int RefineMilliseconds = 100;

bool IsHybridOctree(vtkSMProxy* repr)
{
  return repr && repr->GetProperty("Representation") &&
    std::strcmp(vtkSMPropertyHelper(repr, "Representation").GetAsString(),
      pqHybridOctreeBehavior::TypeName()) == 0;
}
}

pqHybridOctreeBehavior::pqHybridOctreeBehavior(QObject* parent)
  : Superclass(parent)
{
}

pqHybridOctreeBehavior::~pqHybridOctreeBehavior() = default;

void pqHybridOctreeBehavior::startup()
{
  pqServerManagerModel* model = pqApplicationCore::instance()->getServerManagerModel();
  QObject::connect(model, &pqServerManagerModel::representationAdded, this,
    &pqHybridOctreeBehavior::onRepresentationAdded);
  QObject::connect(model, &pqServerManagerModel::preRepresentationRemoved, this,
    &pqHybridOctreeBehavior::onRepresentationRemoved);
  QObject::connect(
    model, &pqServerManagerModel::viewAdded, this, &pqHybridOctreeBehavior::onViewAdded);
  // The plugin may be loaded after views and representations exist.
  for (pqView* view : model->findItems<pqView*>())
  {
    this->onViewAdded(view);
  }
  for (pqRepresentation* repr : model->findItems<pqRepresentation*>())
  {
    this->onRepresentationAdded(repr);
  }
}

void pqHybridOctreeBehavior::shutdown()
{
  this->Connections->Disconnect();
  this->Watched.clear();
}

void pqHybridOctreeBehavior::onViewAdded(pqView* view)
{
  QObject::connect(view, &pqView::endRender, this, &pqHybridOctreeBehavior::onEndRender);
}

void pqHybridOctreeBehavior::onRepresentationAdded(pqRepresentation* repr)
{
  vtkSMProxy* proxy = repr ? repr->getProxy() : nullptr;
  vtkSMProperty* type = proxy ? proxy->GetProperty("Representation") : nullptr;
  if (!type || !proxy->GetProperty(OwnProperty))
  {
    return; // not a representation that offers "Hybrid Octree Volume"
  }
  this->Watched.insert(type, repr);
  this->Connections->Connect(
    type, vtkCommand::ModifiedEvent, this, SLOT(onTypeModified(vtkObject*)));
}

void pqHybridOctreeBehavior::onRepresentationRemoved(pqRepresentation* repr)
{
  vtkSMProxy* proxy = repr ? repr->getProxy() : nullptr;
  vtkSMProperty* type = proxy ? proxy->GetProperty("Representation") : nullptr;
  if (type && this->Watched.remove(type) > 0)
  {
    this->Connections->Disconnect(type, vtkCommand::ModifiedEvent, this);
  }
}

void pqHybridOctreeBehavior::onTypeModified(vtkObject* property)
{
  // Run once the type change has returned (the property is modified inside
  // SetRepresentationType): the colouring is then its own step in the undo
  // stack and in a Python trace (ColorBy, RescaleTransferFunctionToDataRange),
  // so a replayed trace colours as the GUI did.
  // A state being loaded (from the GUI or Python) sets the type too: what
  // it holds stays as it is (known only now, not when the deferred call runs).
  QPointer<pqRepresentation> repr = this->Watched.value(property);
  vtkSMSessionProxyManager* pxm = repr ? repr->getProxy()->GetSessionProxyManager() : nullptr;
  if (!pxm || pxm->GetInLoadXMLState() || pqApplicationCore::instance()->isLoadingState())
  {
    return;
  }
  QTimer::singleShot(0, this, [repr]() { pqHybridOctreeBehavior::OnPicked(repr); });
}

void pqHybridOctreeBehavior::OnPicked(pqRepresentation* repr)
{
  vtkSMProxy* proxy = repr ? repr->getProxy() : nullptr;
  if (!IsHybridOctree(proxy))
  {
    return;
  }
  BEGIN_UNDO_SET("Color Hybrid Octree Volume");
  vtkSMViewProxy* view = repr->getView() ? repr->getView()->getViewProxy() : nullptr;
  if (pqHybridOctreeBehavior::ColorByFirstArray(proxy) && view)
  {
    pqDisplayColorWidget::updateScalarBarVisibility(view, proxy);
  }
  pqHybridOctreeBehavior::DefaultIsovalue(proxy);
  proxy->UpdateVTKObjects();
  END_UNDO_SET();
  repr->renderViewEventually();
}

bool pqHybridOctreeBehavior::ColorByFirstArray(vtkSMProxy* repr)
{
  auto pvrepr = vtkSMPVRepresentationProxy::SafeDownCast(repr);
  vtkSMProperty* colorArray = repr ? repr->GetProperty("ColorArrayName") : nullptr;
  if (!pvrepr || !colorArray || pvrepr->GetUsingScalarColoring())
  {
    return false;
  }
  auto arrays = colorArray->FindDomain<vtkSMArrayListDomain>();
  if (!arrays || arrays->GetNumberOfStrings() == 0)
  {
    return false; // nothing to colour by: the mapper says so when drawing
  }
  // A point array if there is one (the mapper draws point data), as
  // vtkSMPVRepresentationProxy::SetRepresentationType does for "Volume".
  unsigned int index = 0;
  for (unsigned int i = 0; i < arrays->GetNumberOfStrings(); ++i)
  {
    if (arrays->GetFieldAssociation(i) == vtkDataObject::POINT)
    {
      index = i;
      break;
    }
  }
  if (!pvrepr->SetScalarColoring(arrays->GetString(index), arrays->GetFieldAssociation(index)))
  {
    return false;
  }
  pvrepr->RescaleTransferFunctionToDataRange(true);
  return true;
}

void pqHybridOctreeBehavior::DefaultIsovalue(vtkSMProxy* repr)
{
  vtkSMProperty* isovalue = repr->GetProperty("OctreeIsovalue");
  if (isovalue && isovalue->IsValueDefault())
  {
    isovalue->ResetToDomainDefaults();
  }
}

void pqHybridOctreeBehavior::onEndRender()
{
  auto view = qobject_cast<pqView*>(this->sender());
  if (!view)
  {
    return;
  }
  bool loading = false;
  for (pqRepresentation* repr : view->getRepresentations())
  {
    vtkSMProxy* proxy = repr->getProxy();
    if (repr->isVisible() && IsHybridOctree(proxy))
    {
      // The information-only properties: the statistics among them.
      proxy->UpdatePropertyInformation();
      loading = loading ||
        (proxy->GetProperty("LastBricksLoading") &&
          vtkSMPropertyHelper(proxy, "LastBricksLoading").GetAsInt() > 0);
    }
  }
  if (loading)
  {
    // Asynchronous Loading: bricks are still arriving, so the view draws
    // again shortly (each frame shows what has arrived since).
    QPointer<pqView> still(view);
    QTimer::singleShot(RefineMilliseconds, this, [still]() {
      if (still)
      {
        still->render();
      }
    });
  }
}
