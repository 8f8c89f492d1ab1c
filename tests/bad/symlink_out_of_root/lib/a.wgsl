#import escape
