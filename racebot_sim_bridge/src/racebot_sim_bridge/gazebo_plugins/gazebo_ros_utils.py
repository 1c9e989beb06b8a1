"""GazeboRosPlugin: what gazebo_plugins' GazeboRos helper (gazebo_ros_utils.cpp, noetic-devel) gives the plugins
built on it (diff_drive, tricycle_drive): rosDebugLevel, the parameters left out logged with their defaults,
joints found by name with a default, the odometrySource choice. Its namespace rule is plugin_namespace's
'gazebo_ros' kind; its resolveTF is odometry_output.tf_resolve under tf_prefix."""
from racebot_sim_bridge.gazebo_plugins.model_plugin import ModelPlugin, PluginError

LOG_LEVELS = ('debug', 'info', 'warn', 'error', 'fatal')  # rosDebugLevel's values, any case
ODOMETRY_SOURCES = ('encoder', 'world')


class GazeboRosPlugin(ModelPlugin):
    def __init__(self, ctx, robot, spec, defaults=()):
        """`defaults`: ((tag, default text), ...) GazeboRos would log as missing (ROS_WARN upstream, one info
        line here)."""
        super().__init__(ctx, robot, spec)
        level = self.params.string('rosDebugLevel', 'na').strip().lower()  # read first, as GazeboRos does
        self.log_level = LOG_LEVELS.index(level) if level in LOG_LEVELS else LOG_LEVELS.index('info')
        missing = ['<%s> %s' % (tag, value) for tag, value in defaults if not self.params.has(tag)]
        if missing:
            self.info('defaults used for the parameters not given: %s' % ', '.join(missing))

    # -- logging at rosDebugLevel ----------------------------------------------------------------
    def warn(self, message):
        if self.log_level <= LOG_LEVELS.index('warn'):
            super().warn(message)

    def info(self, message):
        if self.log_level <= LOG_LEVELS.index('info'):
            super().info(message)

    # -- parameters --------------------------------------------------------------------------------
    def named_joint(self, tag, default, what):
        """GazeboRos::getJoint: the joint <tag> names, else `default`; PluginError when it is no movable joint
        (upstream throws, and Gazebo drops the plugin)."""
        if self.params.has(tag):
            return self.joint(tag)
        joint = self.robot.body.joints.get(default)
        if joint is None:
            raise PluginError("<%s> is missing and the default %s joint '%s' is not a movable joint of the "
                              "robot: name the %s joint (its joints: %s)"
                              % (tag, what, default, what, ', '.join(sorted(self.robot.body.joints)) or 'none'))
        return joint

    def odometry_source(self):
        """<odometrySource>: 'encoder' or 'world' (GazeboRos's enum lookup; anything else: world, with a warning)."""
        text = self.params.string('odometrySource', 'world')
        if text in ODOMETRY_SOURCES:
            return text
        hint = (' (gazebo_plugins noetic matches the names only, not the enum numbers 0 and 1)'
                if text.strip() in ('0', '1') else '')
        self.warn('<odometrySource>%s</odometrySource> must be encoder or world%s; using world' % (text, hint))
        return 'world'
