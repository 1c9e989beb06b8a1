"""Who provides a package name: racebot (its devel space), an installed package rospack finds (Debian's
/usr/share/<pkg>, an underlay), a Debian package rosdep resolves it to, or nobody (then it is built from source).

rosdep is asked through its own library (rosdep2: the sources cache `rosdep update` wrote, the platform given as
debian:bookworm), one process for every name, as `rosdep resolve` does; rospack through rospkg.
"""
import os

DEBIAN = ('debian', 'bookworm')
# rosdep keys of Gazebo 11's development files (rosdistro's base.yaml: Ubuntu rules only), which packages name
# beside or instead of `gazebo` (ridgeback_gazebo_plugins: <build_depend>libgazebo11-dev</build_depend>): the
# find_package(gazebo) racebot answers answers them too
GAZEBO_KEYS = ('gazebo11', 'libgazebo11-dev')


class Provider:
    """One answer: `kind` is 'racebot', 'installed', 'debian' (with the apt packages and those of them not
    installed yet) or 'source' (with why not the others, for the report)."""

    def __init__(self, kind, where='', packages=(), missing=()):
        self.kind, self.where, self.packages, self.missing = kind, where, list(packages), list(missing)

    def __repr__(self):
        return 'Provider(%r, %r)' % (self.kind, self.where or self.packages)


class Providers:
    """Answers `provider(name)` for the environment it was made in (racebot's devel space sourced) and rosdep's
    sources cache in `ros_home`."""

    def __init__(self, racebot_root, ros_home, give_way=()):
        import rospkg
        self.racebot_root = os.path.realpath(racebot_root)
        self.rospack = rospkg.RosPack()
        self.give_way = set(give_way)
        self._rosdep = _RosdepResolver(ros_home)

    def provider(self, name):
        if name in self.give_way:
            return Provider('source', 'a racebot stand-in that gives way to the real package')
        try:
            path = os.path.realpath(self.rospack.get_path(name))
        except Exception:  # rospkg.ResourceNotFound, or a broken manifest: not provided
            path = None
        if path:
            kind = 'racebot' if path.startswith(self.racebot_root + os.sep) else 'installed'
            return Provider(kind, path)
        config = self.cmake_config('gazebo' if name in GAZEBO_KEYS else name)
        if config:
            return Provider('racebot', config)
        resolved, packages, why = self._rosdep.resolve(name)
        if resolved:
            return Provider('debian', 'rosdep', packages, self._rosdep.not_installed(packages))
        return Provider('source', why)

    def cmake_config(self, name):
        """The CMake package configuration racebot's devel space has for `name`, or None: a system dependency such as
        `gazebo` (rosdep's key for Gazebo 11 on Ubuntu, no rule for Debian) that is no ROS package but whose
        find_package racebot answers (docs/SUPPORTED.md, racebot's Gazebo plugin API)."""
        for devel in os.environ.get('CMAKE_PREFIX_PATH', '').split(os.pathsep):
            if not devel or not os.path.realpath(devel).startswith(self.racebot_root + os.sep):
                continue
            for base in ('%s-config.cmake' % name, '%sConfig.cmake' % name):
                path = os.path.join(devel, 'lib', 'cmake', name, base)
                if os.path.isfile(path):
                    return path
        return None


class _RosdepResolver:
    """rosdep2's lookup for debian:bookworm over the sources cache in ros_home/rosdep/sources.cache."""

    def __init__(self, ros_home):
        from rosdep2 import create_default_installer_context, get_default_installer
        from rosdep2.lookup import RosdepLookup
        from rosdep2.rospkg_loader import DEFAULT_VIEW_KEY
        from rosdep2.sources_list import SourcesListLoader
        loader = SourcesListLoader.create_default(sources_cache_dir=os.path.join(ros_home, 'rosdep', 'sources.cache'),
                                                  os_override=DEBIAN)
        self.lookup = RosdepLookup.create_from_rospkg(sources_loader=loader)
        self.view = self.lookup.get_rosdep_view(DEFAULT_VIEW_KEY)
        self.context = create_default_installer_context()
        self.context.set_os_override(*DEBIAN)
        _, self.installer_keys, self.default_key, _, _ = get_default_installer(installer_context=self.context)

    def resolve(self, name):
        """(True, Debian packages (none for a rule that needs nothing), '') or (False, [], why not)."""
        try:
            definition = self.view.lookup(name)
        except KeyError:
            return False, [], 'no rosdep rule'
        try:
            installer_key, rule = definition.get_rule_for_platform(DEBIAN[0], DEBIAN[1], self.installer_keys,
                                                                   self.default_key)
            packages = self.context.get_installer(installer_key).resolve(rule)
        except Exception as error:  # rosdep2.ResolutionError and the installers' InvalidData
            return False, [], 'no rosdep rule for %s:%s (%s)' % (DEBIAN + (str(error).splitlines()[0],))
        return True, [str(p) for p in packages], ''

    def not_installed(self, packages):
        installer = self.context.get_installer('apt')
        try:
            return list(installer.get_packages_to_install(packages))
        except Exception:  # dpkg-query missing: say every package may be missing
            return list(packages)
