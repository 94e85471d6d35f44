#include "viewer_window.hpp"

#include <algorithm>
#include <cmath>
#include <exception>
#include <utility>

#include <QAction>
#include <QApplication>
#include <QCursor>
#include <QDir>
#include <QFileDialog>
#include <QHBoxLayout>
#include <QHeaderView>
#include <QImage>
#include <QKeySequence>
#include <QLabel>
#include <QLineEdit>
#include <QListWidget>
#include <QMenuBar>
#include <QMessageBox>
#include <QPixmap>
#include <QPushButton>
#include <QScreen>
#include <QScrollBar>
#include <QSignalBlocker>
#include <QSlider>
#include <QSplitter>
#include <QStatusBar>
#include <QStyle>
#include <QTableWidget>
#include <QTimer>
#include <QToolButton>
#include <QVBoxLayout>

#include "rwsim/simulator/grasp_trial.hpp"
#include "visgrab/render/srgb.hpp"
#include "visgrab/view/grasp_pictures.hpp"

namespace visgrab::viewer {

namespace {

using rwsim::trial::GraspOutcome;

constexpr int kPlayIntervalMs = 30;
constexpr int kStatusMs = 8000;
constexpr int kMaxGraspTableWidth = 560;
constexpr int kGraspTableWidth = 460;
constexpr int kSceneListWidth = 270;
constexpr int kControlsHeight = 130;  // menu, replay controls, caption, status bar

enum GraspColumn {
  kNumberColumn,
  kMethodColumn,
  kIdColumn,
  kOutcomeColumn,
  kQLiftColumn,
  kQGwsColumn,
  kQGwsUnitColumn,
  kColumnCount
};

QString qs(const std::string& text) { return QString::fromStdString(text); }

// An outcome's colour (the report's) as a Qt colour.
QColor outcomeQColor(GraspOutcome outcome) {
  const Eigen::Vector3f linear = view::outcomeColour(outcome);
  const auto encode = [](float c) {
    return static_cast<int>(std::lround(255.0f * render::encodeSrgb(c)));
  };
  return QColor(encode(linear.x()), encode(linear.y()), encode(linear.z()));
}

QIcon swatch(const QColor& colour) {
  QPixmap pixmap(12, 12);
  pixmap.fill(colour);
  return QIcon(pixmap);
}

// `value` with `decimals` decimals; "–" for NaN (a Q_GWS not computed, from older results).
QString number(double value, int decimals) {
  return std::isnan(value) ? QString::fromUtf8("–") : QString::number(value, 'f', decimals);
}

// The busy cursor while a long operation runs.
class BusyCursor {
 public:
  BusyCursor() { QApplication::setOverrideCursor(QCursor(Qt::WaitCursor)); }
  ~BusyCursor() { QApplication::restoreOverrideCursor(); }
  BusyCursor(const BusyCursor&) = delete;
  BusyCursor& operator=(const BusyCursor&) = delete;
};

}  // namespace

ViewerWindow::ViewerWindow(ViewerData loaded, const ViewerOptions& options, QWidget* parent)
    : QMainWindow(parent), data_(std::move(loaded)) {
  buildWidgets();
  buildMenus();
  const QSize viewSize(options.width, options.height);
  if (options.screenshot) {
    view_->setFixedSize(viewSize);
  } else {
    view_->setPreferredSize(viewSize);
  }
  // Room for the view at the size asked for, within the screen.
  const int tableWidth = data_.haveGraspFiles ? kGraspTableWidth : 0;
  splitter_->setSizes({kSceneListWidth, viewSize.width(), tableWidth});
  QSize windowSize(kSceneListWidth + viewSize.width() + tableWidth + 32,
                   viewSize.height() + kControlsHeight);
  if (const QScreen* s = screen(); s != nullptr && !options.screenshot) {
    windowSize = windowSize.boundedTo(s->availableGeometry().size());
  }
  resize(windowSize);
  setWindowTitle("VisGraB viewer");
  statusBar()->addPermanentWidget(
      new QLabel(qs(data_.databasePath.string() + "   hand " + data_.hand->deviceName()), this));
}

ViewerWindow::~ViewerWindow() {
  // The view's drawing refers to the session's workcell: it goes first.
  view_->setSession(nullptr);
}

void ViewerWindow::buildWidgets() {
  splitter_ = new QSplitter(Qt::Horizontal, this);
  QSplitter* splitter = splitter_;

  // Left: the scenes with a filter.
  auto* left = new QWidget(splitter);
  auto* leftLayout = new QVBoxLayout(left);
  leftLayout->setContentsMargins(4, 4, 4, 4);
  filter_ = new QLineEdit(left);
  filter_->setPlaceholderText("filter scenes (words of the id)");
  filter_->setClearButtonEnabled(true);
  scenes_ = new QListWidget(left);
  for (std::size_t i = 0; i < data_.database->list().size(); ++i) {
    auto* item = new QListWidgetItem(qs(data_.database->list()[i].id), scenes_);
    item->setData(Qt::UserRole, static_cast<qulonglong>(i));
  }
  scenes_->setMinimumWidth(200);
  leftLayout->addWidget(filter_);
  leftLayout->addWidget(scenes_);
  connect(filter_, &QLineEdit::textChanged, this, &ViewerWindow::filterScenes);
  connect(scenes_, &QListWidget::itemSelectionChanged, this, &ViewerWindow::sceneSelected);

  // Middle: the 3-D view over the replay controls.
  auto* middle = new QWidget(splitter);
  auto* middleLayout = new QVBoxLayout(middle);
  middleLayout->setContentsMargins(0, 0, 0, 0);
  view_ = new SceneView(middle);
  middleLayout->addWidget(view_, 1);
  auto* controls = new QHBoxLayout();
  play_ = new QToolButton(middle);
  play_->setIcon(style()->standardIcon(QStyle::SP_MediaPlay));
  play_->setToolTip("Play or pause the replay (space)");
  slider_ = new QSlider(Qt::Horizontal, middle);
  slider_->setToolTip("Time through the replayed trial");
  slider_->setMinimumWidth(120);
  placed_ = new QPushButton("Placed", middle);
  placed_->setToolTip("The hand placed, before closing");
  closed_ = new QPushButton("Closed", middle);
  closed_->setToolTip("The fingers closed");
  lifted_ = new QPushButton("Lifted", middle);
  lifted_->setToolTip("After lifting");
  controls->addWidget(play_);
  controls->addWidget(slider_, 1);
  controls->addWidget(placed_);
  controls->addWidget(closed_);
  controls->addWidget(lifted_);
  middleLayout->addLayout(controls);
  info_ = new QLabel(middle);
  info_->setTextFormat(Qt::RichText);
  info_->setTextInteractionFlags(Qt::TextSelectableByMouse);
  info_->setWordWrap(true);
  middleLayout->addWidget(info_);
  connect(play_, &QToolButton::clicked, this, &ViewerWindow::togglePlay);
  connect(view_, &SceneView::playPauseRequested, this, &ViewerWindow::togglePlay);
  connect(slider_, &QSlider::valueChanged, this, [this](int value) {
    setPlaying(false);
    showFrame(static_cast<std::size_t>(std::max(0, value)));
  });
  connect(placed_, &QPushButton::clicked, this, [this] { showMoment(Moment::kPlaced); });
  connect(closed_, &QPushButton::clicked, this, [this] { showMoment(Moment::kClosed); });
  connect(lifted_, &QPushButton::clicked, this, [this] { showMoment(Moment::kLifted); });
  connect(view_, &SceneView::renderError, this,
          [this](const QString& message) { statusBar()->showMessage(message); });

  // Right: the scene's grasps.
  graspTable_ = new QTableWidget(0, kColumnCount, splitter);
  graspTable_->setHorizontalHeaderLabels(
      {"#", "method", "id", "outcome", "Q_lift", "Q_GWS", "Q_GWS,unit"});
  graspTable_->setSelectionBehavior(QAbstractItemView::SelectRows);
  graspTable_->setSelectionMode(QAbstractItemView::SingleSelection);
  graspTable_->setEditTriggers(QAbstractItemView::NoEditTriggers);
  graspTable_->verticalHeader()->setVisible(false);
  graspTable_->horizontalHeader()->setStretchLastSection(true);
  graspTable_->setVisible(data_.haveGraspFiles);
  connect(graspTable_, &QTableWidget::itemSelectionChanged, this, &ViewerWindow::graspSelected);

  splitter->addWidget(left);
  splitter->addWidget(middle);
  splitter->addWidget(graspTable_);
  splitter->setStretchFactor(0, 0);
  splitter->setStretchFactor(1, 1);
  splitter->setStretchFactor(2, 0);
  setCentralWidget(splitter);

  timer_ = new QTimer(this);
  timer_->setInterval(kPlayIntervalMs);
  connect(timer_, &QTimer::timeout, this, &ViewerWindow::playTick);
  clearReplay();
}

void ViewerWindow::buildMenus() {
  QMenu* file = menuBar()->addMenu("&File");
  QAction* save = file->addAction("&Save screenshot...", this, &ViewerWindow::saveScreenshot);
  save->setShortcut(QKeySequence::Save);
  file->addSeparator();
  QAction* quit = file->addAction("&Quit", this, &QWidget::close);
  quit->setShortcut(QKeySequence::Quit);

  // The view's keys act only while the view has the focus (the filter box takes digits).
  QMenu* viewMenu = menuBar()->addMenu("&View");
  const auto viewAction = [&](const QString& text, const QKeySequence& key, auto slot) {
    QAction* action = viewMenu->addAction(text, view_, slot);
    action->setShortcut(key);
    action->setShortcutContext(Qt::WidgetShortcut);
    view_->addAction(action);
    return action;
  };
  viewAction("&Frame objects and hand", QKeySequence(Qt::Key_F), [this] { view_->reframe(); });
  viewMenu->addSeparator();
  viewAction("&Oblique", QKeySequence(Qt::Key_1),
             [this] { view_->setPreset(view::ViewPreset::kOblique); });
  viewAction("F&ront", QKeySequence(Qt::Key_2),
             [this] { view_->setPreset(view::ViewPreset::kFront); });
  viewAction("&Side", QKeySequence(Qt::Key_3),
             [this] { view_->setPreset(view::ViewPreset::kSide); });
  viewAction("&Top", QKeySequence(Qt::Key_4), [this] { view_->setPreset(view::ViewPreset::kTop); });
  viewMenu->addSeparator();
  QAction* contacts = viewMenu->addAction("&Contact forces");
  contacts->setCheckable(true);
  contacts->setChecked(true);
  connect(contacts, &QAction::toggled, view_, &SceneView::setContactsVisible);

  QMenu* replay = menuBar()->addMenu("&Replay");
  QAction* play = replay->addAction("&Play / pause", this, &ViewerWindow::togglePlay);
  play->setShortcut(QKeySequence(Qt::Key_Space));
  play->setShortcutContext(Qt::WidgetShortcut);
  view_->addAction(play);
  replay->addAction("Hand p&laced", this, [this] { showMoment(Moment::kPlaced); });
  replay->addAction("Fingers &closed", this, [this] { showMoment(Moment::kClosed); });
  replay->addAction("After &lifting", this, [this] { showMoment(Moment::kLifted); });

  QMenu* help = menuBar()->addMenu("&Help");
  help->addAction("&Controls", this, &ViewerWindow::showControls);
}

void ViewerWindow::filterScenes(const QString& text) {
  const QStringList words = text.split(' ', Qt::SkipEmptyParts);
  for (int row = 0; row < scenes_->count(); ++row) {
    QListWidgetItem* item = scenes_->item(row);
    const bool match = std::all_of(words.begin(), words.end(), [&](const QString& w) {
      return item->text().contains(w, Qt::CaseInsensitive);
    });
    item->setHidden(!match);
  }
}

void ViewerWindow::openScene(const std::string& id) {
  const auto& list = data_.database->list();
  if (list.empty()) throw std::runtime_error("the database has no scenes");
  const database::SceneEntry& entry = id.empty() ? list.front() : data_.database->scene(id);
  setPlaying(false);
  clearReplay();
  view_->setSession(nullptr);
  session_.reset();
  grasps_.clear();
  fillGraspTable();
  setWindowTitle("VisGraB viewer");
  {
    BusyCursor busy;
    if (!loader_) {
      loader_ = std::make_unique<session::SceneLoader>(*data_.database, *data_.hand, data_.engine);
      loader_->setProtocol(data_.protocol);
    }
    session_ = std::make_unique<session::SceneSession>(*loader_, entry);
  }
  view_->setSession(session_.get());
  if (data_.haveGraspFiles) {
    grasps_ = session::sceneGrasps(*data_.database, entry, data_.grasps,
                                   data_.results ? &*data_.results : nullptr);
  }
  fillGraspTable();
  info_->setText(!data_.haveGraspFiles ? QString("no grasp files (give --grasps or --results)")
                 : grasps_.empty()     ? QString("the grasp files have no grasps for this scene")
                 : !data_.replayProblem.empty()
                     ? QString("trials are not replayed: the run's protocol is not found")
                     : QString("select a grasp to replay its trial"));
  setWindowTitle(qs(entry.id) + " - VisGraB viewer");
  {
    const QSignalBlocker block(scenes_);
    for (int row = 0; row < scenes_->count(); ++row) {
      if (scenes_->item(row)->text() == qs(entry.id)) scenes_->setCurrentRow(row);
    }
  }
  statusBar()->showMessage(
      QString("%1: %2 grasps").arg(qs(entry.id)).arg(static_cast<qulonglong>(grasps_.size())),
      kStatusMs);
}

void ViewerWindow::sceneSelected() {
  const QList<QListWidgetItem*> selected = scenes_->selectedItems();
  if (selected.isEmpty()) return;
  const auto index = static_cast<std::size_t>(selected.front()->data(Qt::UserRole).toULongLong());
  const std::string id = data_.database->list().at(index).id;
  try {
    openScene(id);
  } catch (const std::exception& e) {
    reportError("Cannot open scene " + qs(id), e.what());
  }
}

void ViewerWindow::fillGraspTable() {
  const QSignalBlocker block(graspTable_);
  graspTable_->clearContents();
  graspTable_->setRowCount(static_cast<int>(grasps_.size()));
  for (std::size_t i = 0; i < grasps_.size(); ++i) {
    const session::SceneGrasp& g = grasps_[i];
    const int row = static_cast<int>(i);
    const auto cell = [&](int column, const QString& text) {
      auto* item = new QTableWidgetItem(text);
      if (column == kNumberColumn || column == kQLiftColumn || column == kQGwsColumn ||
          column == kQGwsUnitColumn) {
        item->setTextAlignment(Qt::AlignRight | Qt::AlignVCenter);
      }
      graspTable_->setItem(row, column, item);
      return item;
    };
    cell(kNumberColumn, QString::number(row + 1));
    cell(kMethodColumn, qs(g.request.method));
    cell(kIdColumn, qs(g.request.id));
    if (g.record) {
      QTableWidgetItem* outcome =
          cell(kOutcomeColumn, qs(std::string(rwsim::trial::outcomeName(g.record->outcome))));
      outcome->setIcon(swatch(outcomeQColor(g.record->outcome)));
      cell(kQLiftColumn, number(g.record->qLift, 3));
      cell(kQGwsColumn, number(g.record->qGws, 4));
      cell(kQGwsUnitColumn, number(g.record->qGwsUnit, 4));
    } else {
      cell(kOutcomeColumn, data_.results ? "not run" : "");
      cell(kQLiftColumn, "");
      cell(kQGwsColumn, "");
      cell(kQGwsUnitColumn, "");
    }
  }
  fitGraspTable();
}

void ViewerWindow::fitGraspTable() {
  graspTable_->resizeColumnsToContents();
  int width = 2 * graspTable_->frameWidth() + graspTable_->verticalScrollBar()->sizeHint().width();
  for (int column = 0; column < kColumnCount; ++column) width += graspTable_->columnWidth(column);
  graspTable_->setMinimumWidth(std::min(width, kMaxGraspTableWidth));
}

void ViewerWindow::graspSelected() {
  const QList<QTableWidgetItem*> selected = graspTable_->selectedItems();
  if (selected.isEmpty()) return;
  const auto index = static_cast<std::size_t>(selected.front()->row());
  if (index >= grasps_.size()) return;
  const QString problem = replayGrasp(index);
  if (!problem.isEmpty()) {
    if (!data_.replayProblem.empty()) {
      reportError("Cannot replay the trial", qs(data_.replayProblem));
    } else {
      statusBar()->showMessage(problem);
    }
    return;
  }
  showFrame(0);
  setPlaying(true);
}

QString ViewerWindow::openGrasp(const std::string& spec, const std::string& method) {
  const session::SceneGrasp& grasp = session::selectGrasp(grasps_, spec, method);
  const auto index = static_cast<std::size_t>(&grasp - grasps_.data());
  {
    const QSignalBlocker block(graspTable_);
    graspTable_->selectRow(static_cast<int>(index));
  }
  return replayGrasp(index);
}

QString ViewerWindow::replayGrasp(std::size_t index) {
  setPlaying(false);
  clearReplay();
  const session::SceneGrasp& grasp = grasps_.at(index);
  const QString name = qs(grasp.request.method + " " + grasp.request.id);
  const view::DrawStyle noHand{false, true, std::nullopt};
  if (!data_.replayProblem.empty()) {
    // The run's protocol is not found: another protocol would replay other trials.
    view_->showState(session_->initialState(), {}, noHand);
    const QString reason = QString("%1 cannot be replayed: %2").arg(name, qs(data_.replayProblem));
    info_->setText(reason.toHtmlEscaped());
    return reason;
  }
  const grasp::ResolvedGrasp resolved = session_->resolve(grasp.request);
  if (!resolved.placed()) {
    view_->showState(session_->initialState(), {}, noHand);
    const QString reason =
        QString("%1 cannot be placed (%2): %3")
            .arg(name, grasp::resolveStatusName(resolved.status), qs(resolved.message));
    info_->setText(reason.toHtmlEscaped());
    return reason;
  }
  statusBar()->showMessage("Replaying " + name + " ...");
  statusBar()->repaint();
  try {
    BusyCursor busy;
    replay_ = view::replayTrial(session_->trial(), resolved.parameters, session_->initialState());
  } catch (const std::exception& e) {
    view_->showState(session_->initialState(), {}, noHand);
    const QString reason = QString("%1 cannot be simulated: %2").arg(name, e.what());
    info_->setText(reason.toHtmlEscaped());
    return reason;
  }
  replayedGrasp_ = index;
  const GraspOutcome outcome = replay_->result.outcome;
  if (grasp.record && view::replayDiffers(*grasp.record, replay_->result)) {
    replayNote_ =
        QString(
            "the results say %1 after %2 s (another build, hand, database or protocol than "
            "the run's?)")
            .arg(qs(std::string(rwsim::trial::outcomeName(grasp.record->outcome))))
            .arg(grasp.record->simulatedTime);
  }
  if (!grasp.record) showReplayedOutcome(index);
  std::vector<SceneView::FramedPart> framed{{session_->initialState(), false}};
  framed.push_back({replay_->frames.at(replay_->placed).state, true});
  framed.push_back({replay_->frames.at(replay_->lifted).state, true});
  view_->setFramed(std::move(framed));
  view_->reframe();
  const int last = static_cast<int>(replay_->frames.size()) - 1;
  {
    const QSignalBlocker block(slider_);
    slider_->setRange(0, last);
  }
  for (QWidget* w : std::initializer_list<QWidget*>{play_, slider_, placed_, closed_, lifted_}) {
    w->setEnabled(true);
  }
  showMoment(Moment::kPlaced);
  statusBar()->showMessage(
      QString("%1: %2").arg(name, qs(std::string(rwsim::trial::outcomeName(outcome)))), kStatusMs);
  return {};
}

void ViewerWindow::showReplayedOutcome(std::size_t index) {
  // Not in the results: the replayed outcome fills the table's row, in italics.
  const GraspOutcome outcome = replay_->result.outcome;
  const int row = static_cast<int>(index);
  const QSignalBlocker block(graspTable_);
  const auto set = [&](int column, const QString& text) {
    auto* item = new QTableWidgetItem(text);
    QFont font = item->font();
    font.setItalic(true);
    item->setFont(font);
    if (column != kOutcomeColumn) item->setTextAlignment(Qt::AlignRight | Qt::AlignVCenter);
    graspTable_->setItem(row, column, item);
    return item;
  };
  set(kOutcomeColumn, qs(std::string(rwsim::trial::outcomeName(outcome))))
      ->setIcon(swatch(outcomeQColor(outcome)));
  set(kQLiftColumn, number(replay_->result.qLift, 3));
  set(kQGwsColumn, number(replay_->result.qGws, 4));
  set(kQGwsUnitColumn, number(replay_->result.qGwsUnit, 4));
  fitGraspTable();
}

void ViewerWindow::clearReplay() {
  replay_.reset();
  replayedGrasp_.reset();
  replayNote_.clear();
  frame_ = 0;
  for (QWidget* w : std::initializer_list<QWidget*>{play_, slider_, placed_, closed_, lifted_}) {
    w->setEnabled(false);
  }
  {
    const QSignalBlocker block(slider_);
    slider_->setRange(0, 0);
  }
  info_->setText("select a grasp to replay its trial");
}

QString ViewerWindow::replayOutcome() const {
  if (!replay_) return {};
  const auto& r = replay_->result;
  return qs(view::outcomeCaption(r.outcome, r.qLift, r.qGws, r.qGwsUnit));
}

void ViewerWindow::showMoment(Moment moment) {
  if (!replay_) return;
  setPlaying(false);
  switch (moment) {
    case Moment::kPlaced:
      showFrame(replay_->placed);
      break;
    case Moment::kClosed:
      showFrame(replay_->closed);
      break;
    case Moment::kLifted:
      showFrame(replay_->lifted);
      break;
  }
}

void ViewerWindow::showFrame(std::size_t index) {
  if (!replay_ || replay_->frames.empty()) return;
  frame_ = std::min(index, replay_->frames.size() - 1);
  const view::ReplayFrame& f = replay_->frames[frame_];
  view::DrawStyle style;
  view_->showState(f.state, f.contacts, style);
  {
    const QSignalBlocker block(slider_);
    slider_->setValue(static_cast<int>(frame_));
  }
  const auto& r = replay_->result;
  const QColor colour = outcomeQColor(r.outcome);
  QString text =
      QString(
          "<b>%1</b> &nbsp; t = %2 s &nbsp; (frame %3 of %4) &nbsp;&nbsp; "
          "<span style=\"color:%5\">&#9632;</span> %6")
          .arg(qs(f.phase).toHtmlEscaped(), number(f.time, 3))
          .arg(static_cast<qulonglong>(frame_ + 1))
          .arg(static_cast<qulonglong>(replay_->frames.size()))
          .arg(colour.name(),
               qs(view::outcomeCaption(r.outcome, r.qLift, r.qGws, r.qGwsUnit)).toHtmlEscaped());
  if (!replayNote_.isEmpty()) text += "<br><i>" + replayNote_.toHtmlEscaped() + "</i>";
  info_->setText(text);
}

void ViewerWindow::togglePlay() {
  if (!replay_) return;
  setPlaying(!timer_->isActive());
}

void ViewerWindow::setPlaying(bool playing) {
  if (playing && replay_) {
    if (frame_ + 1 >= replay_->frames.size()) frame_ = 0;  // at the end: from the start
    playStartTime_ = replay_->frames[frame_].time;
    playClock_.start();
    timer_->start();
  } else {
    timer_->stop();
  }
  play_->setIcon(
      style()->standardIcon(timer_->isActive() ? QStyle::SP_MediaPause : QStyle::SP_MediaPlay));
}

void ViewerWindow::playTick() {
  if (!replay_) {
    setPlaying(false);
    return;
  }
  // Real time: the last frame at or before the time played so far.
  const double t = playStartTime_ + 1e-3 * static_cast<double>(playClock_.elapsed());
  std::size_t next = frame_;
  while (next + 1 < replay_->frames.size() && replay_->frames[next + 1].time <= t) ++next;
  if (next != frame_) showFrame(next);
  if (frame_ + 1 >= replay_->frames.size()) setPlaying(false);
}

void ViewerWindow::saveScreenshot() {
  QString name = "visgrab-view.png";
  if (session_) {
    name = qs(session_->entry().id);
    name.replace('/', '_');
    if (replayedGrasp_) {
      name += "_" + qs(grasps_[*replayedGrasp_].request.method + "_" +
                       grasps_[*replayedGrasp_].request.id);
    }
    name += ".png";
  }
  const QString file = QFileDialog::getSaveFileName(
      this, "Save screenshot", QDir::current().filePath(name), "PNG images (*.png)");
  if (file.isEmpty()) return;
  const QImage image = view_->grabFramebuffer();
  if (image.isNull() || !image.save(file, "PNG")) {
    reportError("Cannot save the screenshot", "writing " + file + " failed");
    return;
  }
  statusBar()->showMessage("saved " + file, kStatusMs);
}

void ViewerWindow::showControls() {
  QMessageBox::information(
      this, "Controls",
      "<p><b>Left-drag</b> orbits, <b>right- or middle-drag</b> pans, the <b>wheel</b> zooms.</p>"
      "<p><b>Double-click</b> or <b>F</b> frames the objects and the hand; <b>1-4</b> look from "
      "the oblique, front, side and top views; <b>space</b> plays and pauses the replay "
      "(with the 3-D view focused).</p>"
      "<p>Select a scene on the left and a grasp on the right to replay its trial; the buttons "
      "below the view jump to the hand placed, the fingers closed and after lifting. "
      "<b>Ctrl+S</b> saves the view as a PNG.</p>");
}

void ViewerWindow::reportError(const QString& what, const QString& message) {
  statusBar()->showMessage(what + ": " + message);
  QMessageBox::warning(this, "VisGraB viewer", what + ":\n" + message);
}

}  // namespace visgrab::viewer
