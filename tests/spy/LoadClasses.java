// Loads and links each class named on the command line from the classpath it runs with, the
// way lcm-spy does when it opens a message; exits 1 naming every class that does not load.
public class LoadClasses {
  public static void main(String[] names) {
    int missing = 0;
    for (String name : names) {
      try {
        Class.forName(name, true, LoadClasses.class.getClassLoader());
      } catch (ClassNotFoundException | LinkageError e) {
        System.err.println(name + ": cannot be loaded: " + e);
        ++missing;
      }
    }
    System.exit(missing == 0 ? 0 : 1);
  }
}
