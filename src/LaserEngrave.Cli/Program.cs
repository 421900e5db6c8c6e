namespace LaserEngrave.Cli;

internal static class Program
{
    public static int Main(string[] args)
    {
        Console.Error.WriteLine("laserengrave: no commands yet");
        return args.Length == 0 ? 2 : 1;
    }
}
