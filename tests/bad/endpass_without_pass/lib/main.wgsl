#shader s
#endpass
