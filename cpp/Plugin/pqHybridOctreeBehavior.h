/**
 * @class   pqHybridOctreeBehavior
 * @brief   The ParaView GUI's side of the "Hybrid Octree Volume" representation.
 *
 * ParaView's client does two things for a representation named "Volume"
 * that it does not know to do for ours (vtkSMPVRepresentationProxy and
 * pqDisplayRepresentationWidget compare the type's name with "Volume"):
 *
 * - picking the type colours the image by its first point array when it was
 *   drawn in a solid colour (and rescales the colour map, and shows the
 *   scalar bar as the general settings say), so the first pick shows the
 *   coloured volume rather than an empty view;
 * - (ours alone) the isovalue, still at its XML default, is set to the middle
 *   of the coloured array's range, the domain's default.
 *
 * And after every render of a view it pulls the last-frame statistics of the
 * Hybrid Octree representations drawn in it (Bricks, Texture MB, Plan, Frame
 * ms, Estimated Error, Points), so the panel shows the frame on screen; when
 * one of them drew bricks by stand-ins while they load from an OME-Zarr
 * store (Asynchronous Loading, Bricks Loading above 0), the view renders
 * again 100 ms later, until every brick has arrived.
 *
 * Loaded with the plugin (an auto-start interface); state files and undo
 * are left alone (nothing is changed while ParaView loads a state).
 */
#ifndef pqHybridOctreeBehavior_h
#define pqHybridOctreeBehavior_h

#include <QMap>
#include <QObject>
#include <QPointer>

#include "vtkNew.h"

class pqRepresentation;
class pqView;
class vtkEventQtSlotConnect;
class vtkObject;
class vtkSMProxy;

class pqHybridOctreeBehavior : public QObject
{
  Q_OBJECT
  typedef QObject Superclass;

public:
  pqHybridOctreeBehavior(QObject* parent = nullptr);
  ~pqHybridOctreeBehavior() override;

  /// Called by the plugin's auto-start interface.
  void startup();
  void shutdown();

  /// The representation type this behaviour serves.
  static const char* TypeName() { return "Hybrid Octree Volume"; }

  /// Colours `repr` by its first point array (a cell array if it has none)
  /// when it is drawn in a solid colour, as ParaView does on picking
  /// "Volume"; returns whether it coloured.
  static bool ColorByFirstArray(vtkSMProxy* repr);

  /// What picking "Hybrid Octree Volume" does: ColorByFirstArray, the
  /// scalar bar, DefaultIsovalue (not called for a type set by a state
  /// being loaded).
  static void OnPicked(pqRepresentation* repr);

  /// Sets the isovalue to its domain's default (mid-range of the coloured
  /// array) when it still holds its XML default.
  static void DefaultIsovalue(vtkSMProxy* repr);

private Q_SLOTS:
  void onRepresentationAdded(pqRepresentation* repr);
  void onRepresentationRemoved(pqRepresentation* repr);
  void onViewAdded(pqView* view);
  void onTypeModified(vtkObject* property);
  void onEndRender();

private:
  Q_DISABLE_COPY(pqHybridOctreeBehavior)

  vtkNew<vtkEventQtSlotConnect> Connections;
  /// The "Representation" property of each watched representation.
  QMap<vtkObject*, QPointer<pqRepresentation>> Watched;
};

#endif
